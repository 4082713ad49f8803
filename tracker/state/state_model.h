// What a particle is and how it moves: one implementation per kind of prior.
//   tracker/state/manifold_state.h     the JGPM family: (phase, gait, stride scale) on the manifold
//   tracker/state/latent_state.h       other GP models and PCA: a point of the latent space
//   tracker/state/joint_space_state.h  the classic baseline without a learned prior: 43 angles
// Every state ends with the same six numbers: where the person stands on the floor (x, z
// in mm, the world's y is up), which way they face (heading, radians about +y, 0 facing
// +z), how fast they go (cadence in cycles per second, or speed in m/s), their size (one
// scale on the skeleton's bone lengths and the body's widths) and their width (one more
// scale on the body's widths alone: a build, or clothes, the adult-average body lacks;
// without it a coat could only be explained by a taller person farther away).
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "io/gait/gait_pose.h"
#include "io/mocap/kinematics.h"
#include "io/mocap/skeleton.h"
#include "tracker/state/proportions.h"
#include "tracker/state/random.h"

namespace jgpm {

// Indices of the shared part, from StateModel::placement().
struct PlacementIndex {
  int x, z, heading, rate, size, width;
};

// The rough where and how big of a person, from initialisation.
struct InitialGuess {
  Eigen::Vector2d floor_mm = Eigen::Vector2d::Zero();  // root (x, z)
  double floor_std_mm = 150;
  // Other places the cameras read (each camera's own, when it differs from floor_mm by
  // more than the locator's error): the start spreads its particles over these as well,
  // equally, and lets the silhouettes choose.
  std::vector<Eigen::Vector2d> other_floors_mm;
  double heading_rad = 0;
  double heading_std_rad = 3.2;  // >= pi: any heading
  double size = 1;
  double size_std = 0.05;
  bool size_seen = true;  // false: no height was measured (the feet or the head unseen)
  double width = 1;
  double width_std = 0.06;
  double speed_mm_s = -1;  // walking speed seen at the start; < 0: unknown
  // The state's own coordinates when known (e.g. from a clip's truth); empty: spread over
  // everything the prior allows. Known ones are spread by a quarter of the diffusion.
  Eigen::VectorXd coordinates;
};

class StateModel {
 public:
  virtual ~StateModel() = default;

  virtual std::string Name() const = 0;
  virtual int Dimension() const = 0;
  PlacementIndex placement() const {
    const int k = Dimension() - 6;
    return {k, k + 1, k + 2, k + 3, k + 4, k + 5};
  }
  // The factor on every body part's radius: size times width.
  double RadiusScale(const double* state) const {
    const PlacementIndex p = placement();
    return state[p.size] * state[p.width];
  }
  // The skeleton whose bone ends Evaluate returns (the model's reference skeleton).
  virtual const Skeleton& skeleton() const = 0;

  // A state drawn around an initial guess (the pose spread over everything the prior allows).
  virtual void Sample(const InitialGuess& guess, Random* random, double* state) const = 0;
  // One frame of the dynamics (`dt` seconds), process noise included.
  virtual void Predict(double dt, Random* random, double* state) const = 0;
  // The annealing's diffusion: Gaussian noise of `scale` times DiffusionStd per dimension,
  // then Normalise.
  void Diffuse(double scale, Random* random, double* state) const;
  virtual Eigen::VectorXd DiffusionStd() const = 0;
  // Moves the rate `share` (0-1) of the way to the one the model gives a person seen going
  // `speed_mm_s` (>= 0; the tracker's pace: the speed its estimates are seen to go), its
  // direction kept (manifold_state.h: a stop's, the one that covers it; a walker's, at
  // least a slow walk's; with `cover`, the one that covers the speed whatever it is: a
  // prediction with no silhouettes to set the cadence). Models whose rate is not a
  // cadence: unchanged.
  virtual void Pace(double /*speed_mm_s*/, double /*share*/, double* /*state*/, bool /*cover*/ = false) const {}
  // Wraps periodic coordinates and clamps bounded ones.
  virtual void Normalise(double* state) const = 0;
  // Period of a coordinate (0: not periodic), for averaging states.
  virtual double Period(int dimension) const;

  // The bone ends in the world (mm, 3 x bones of skeleton()) and ln p(x|M) of the state
  // (0 when the model has no prior). Thread-safe; `joints` is resized when needed.
  virtual double Evaluate(const double* state, Eigen::Matrix3Xd* joints) const = 0;
  // The pose's channels (degrees, the gait pose layout of the model's skeleton).
  virtual Eigen::VectorXd Pose(const double* state) const = 0;
  // The state's own coordinates for people and files (e.g. "phase", "gait", "scale").
  virtual std::vector<std::string> CoordinateNames() const = 0;

  // The person's limb lengths (proportions.h), applied by Evaluate: set between frames
  // (not while particles are evaluated).
  virtual void SetProportions(const Proportions& proportions) { proportions_ = proportions; }
  // The floor's height under the person (mm; 0: the world's y = 0): a ramp, or a floor
  // the calibration puts a little off. Set between frames, like the proportions.
  virtual void SetFloor(double floor_mm) { floor_mm_ = floor_mm; }

 protected:
  Proportions proportions_;
  double floor_mm_ = 0;
};

// Root-relative bone ends (size 1, facing +z, as a pose table or forward kinematics gives
// them) placed in the world: scaled by `size`, turned by `heading_rad` about +y, the root
// at (x, z) and raised so the lowest foot joint is `clearance_mm` above the floor.
void PlaceInWorld(const Eigen::Matrix3Xd& relative, double foot_height_mm, double x_mm, double z_mm,
                  double heading_rad, double size, double clearance_mm, Eigen::Matrix3Xd* world);

// The width's range and how it moves, shared by every state model. Range: the realism
// clips' people span 0.75-1.25 of the average widths (clip_body.h), and a coat or a skirt
// adds up to 30% where they are. Between frames it drifts 0.2% (a build does not change);
// the annealing's first layer spreads it by 2% a frame (the size's 1%: the width is less
// sure at the start), so a first guess 10% off is corrected within about ten frames
// where the silhouettes show it.
constexpr double kMinWidth = 0.75, kMaxWidth = 1.5, kWidthNoise = 0.002, kWidthDiffusion = 0.02;

// Height of the lowest foot joint above the floor while walking (mm): CMU's foot and toe
// bone ends sit on the skin's surface, a shoe's sole lower.
constexpr double kFootClearanceMm = 40;

// Gait poses (channels in degrees) to bone ends in the world, by forward kinematics of a
// skeleton: the exact counterpart of a pose table's lookup.
class PosePlacer {
 public:
  // Copies what it needs from the skeleton. InputError when it lacks a gait joint's bone.
  explicit PosePlacer(const Skeleton& skeleton);
  const GaitPoseLayout& layout() const { return layout_; }
  // Root-relative bone ends (size 1, facing +z, limbs in proportion) and the lowest foot
  // joint's height.
  void Relative(const double* pose, Eigen::Matrix3Xd* relative, double* foot_height_mm) const;
  // Set between placements, not during them.
  void SetProportions(const Proportions& proportions) { proportions_ = proportions; }
  void SetFloor(double floor_mm) { floor_mm_ = floor_mm; }
  // Placed as PlaceInWorld places them.
  void Place(const double* pose, double x_mm, double z_mm, double heading_rad, double size,
             Eigen::Matrix3Xd* world) const;
  // The same with other proportions and floor than the ones set (thread-safe).
  void Relative(const double* pose, const Proportions& proportions, Eigen::Matrix3Xd* relative,
                double* foot_height_mm) const;
  void Place(const double* pose, double x_mm, double z_mm, double heading_rad, double size,
             const Proportions& proportions, double floor_mm, Eigen::Matrix3Xd* world) const;

 private:
  GaitPoseLayout layout_;
  Kinematics kinematics_;
  std::vector<int> feet_;
  LimbScaler limbs_;
  Proportions proportions_;
  double floor_mm_ = 0;
};

}  // namespace jgpm
