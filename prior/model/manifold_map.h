// The JGPM family's manifold coordinates (pose phase, gait position, stride scale) <->
// latent points, by interpolating the learned latent points of the training grid
// (layer x gait x pose): periodic in phase, periodic in gait on a torus and clamped to
// the ends on a cylinder, linear in stride scale between layers and clamped outside them.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "prior/learning/topology.h"
#include "prior/learning/training_set.h"

namespace jgpm {

// A point on the joint gait-pose manifold.
struct ManifoldPoint {
  double phase = 0;  // along the walking cycle, [0, 1); 0 = the cycles' first pose
  double gait = 0;   // position along the gait manifold, in gaits (torus: wraps at G)
  double scale = 1;  // stride scale (the layers' scales, e.g. 0.4 .. 1.25)
};

class ManifoldMap {
 public:
  // `set` and `latent` (N x 3, rows as the set's) must outlive the map; `gait_order` is a
  // permutation of the set's gaits (checked by the caller).
  ManifoldMap(const TrainingSet& set, const Eigen::MatrixXd& latent, std::vector<int> gait_order,
              TopologyShape shape);

  Eigen::Vector3d ToLatent(const ManifoldPoint& point) const;
  // The manifold point whose latent point is nearest x (Gauss-Newton on the interpolation
  // from the nearest training points).
  ManifoldPoint FromLatent(const Eigen::Vector3d& x) const;

 private:
  Eigen::Vector3d LatentAt(int layer, int gait_position, int pose) const;

  const TrainingSet& set_;
  const Eigen::MatrixXd& latent_;
  std::vector<int> gait_order_;
  TopologyShape shape_;
  std::vector<int> layers_by_scale_;
};

}  // namespace jgpm
