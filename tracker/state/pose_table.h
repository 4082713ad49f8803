// A trained gait model's poses, tabulated for the particle filter. Every particle needs
// the joint positions of the model's mean pose at its state, hundreds of times a frame;
// the model gives them in ~11 us (GP mean pose and forward kinematics), a trilinear lookup
// in well under a microsecond. The grid:
//   JGPM family:  phase (periodic, phase_nodes) x gait position (nodes_per_gait per gait;
//                 periodic on a torus) x stride scale (scale_nodes over the layers' range);
//   other models: a box over the training latent points (padded by latent_margin of its
//                 size), latent_nodes per side.
// Each node holds the bone ends of the model's skeleton (mm, root at the origin, facing
// +z, size 1), the lowest foot joint's height, the pose's channels and ln p(x|M): a kernel
// density over the model's latent points (prior/model/latent_density.h) with the width of the
// median distance to the 8th nearest, not the nearest (the model's own LogDensity): with
// the narrow one, the density dips by several nats between neighbouring training cycles,
// so the untempered prior alone outweighs the silhouettes (seen: 65 mm with it, 35 mm
// without it on the 07_01 clip, the filter resampling on the prior alone). The table's
// accuracy against the model is measured in tests/tracker/state/pose_table_test.cc.
#pragma once

#include <array>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "io/mocap/kinematics.h"
#include "prior/model/gait_model.h"

namespace jgpm {

struct PoseTableOptions {
  int phase_nodes = 64;
  int nodes_per_gait = 12;  // error falls as 1/n^2: 10 mm mean between gaits at 4, ~1 mm at 12
  int scale_nodes = 8;
  int latent_nodes = 32;
  double latent_margin = 0.15;
  // The kernel density's width: k-th nearest neighbour (see below). On the realism tuning
  // clips (5 clips, seeds 1-3, bodytrack 14 mean absolute mm) 8 gives 127.5, 4 gives 139.8
  // and 16 gives 132.3.
  int density_neighbours = 8;
  int threads = 1;  // for building

  bool Check(std::string* why) const;
};

class PoseTable {
 public:
  // Builds the table (about 3 s for ML-JGPM's 1800 points on 2 threads).
  PoseTable(const GaitModel& model, const PoseTableOptions& options = {});

  // What the constructor computes, numbered: raise it when that changes (the density, the
  // grid, the foot height...), so that tables kept by an older jgpm are built again.
  static constexpr int kVersion = 1;

  // The table as bytes, with `key` (what it was built from: the caller's choice, e.g. a
  // hash of the model file and the options), to be read back by Parse bit for bit.
  std::string Serialize(const std::string& key) const;
  // The table in `bytes` when they hold `key`; null when they hold another key. InputError
  // naming `source` when the bytes are not a table (truncated, sizes that disagree, not
  // finite).
  static std::unique_ptr<PoseTable> Parse(std::string_view bytes, const std::string& key, const std::string& source);

  bool manifold() const { return manifold_; }
  int NumBones() const { return bones_; }
  int NumChannels() const { return channels_; }
  // Grid coordinates' ranges: [lo, hi) periodic or [lo, hi] clamped.
  const std::array<double, 3>& lo() const { return lo_; }
  const std::array<double, 3>& hi() const { return hi_; }
  bool periodic(int d) const { return periodic_[d]; }

  // Joint positions (3 x bones, relative to the root, size 1, facing +z), the lowest foot
  // joint's height (mm, relative to the root) and ln p(x|M), interpolated at `at`
  // (manifold: phase, gait, scale; latent: the point). Coordinates outside a clamped
  // range are clamped; periodic ones wrap.
  void Lookup(const Eigen::Vector3d& at, Eigen::Matrix3Xd* joints, double* foot_height_mm,
              double* log_density) const;
  // The pose's channels (degrees) at `at`, interpolated.
  Eigen::VectorXd Pose(const Eigen::Vector3d& at) const;
  // JGPM family: the root's travel over one walking cycle (mm, size 1) at a gait position
  // and scale: the stance foot does not slide, so the root moves as far as the lower foot
  // moves back relative to it.
  double StrideMm(double gait, double scale) const;

 private:
  PoseTable() = default;
  struct Corner {
    std::array<int, 8> node;
    std::array<double, 8> weight;
  };
  Corner Corners(const Eigen::Vector3d& at) const;
  int Node(int i, int j, int k) const { return (k * n_[1] + j) * n_[0] + i; }

  bool manifold_ = false;
  int bones_ = 0, channels_ = 0;
  std::array<int, 3> n_{};
  std::array<double, 3> lo_{}, hi_{}, step_{};
  std::array<bool, 3> periodic_{};
  int fast_size_ = 0;            // floats per node in fast_: 3 bones + foot + density
  std::vector<float> fast_;      // per node: joints (x, y, z per bone), foot height, ln p
  std::vector<float> poses_;     // per node: channels
  std::vector<double> stride_;   // JGPM family: per (gait node, scale node)
};

}  // namespace jgpm
