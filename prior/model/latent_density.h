// A kernel density over a model's training latent points: how plausible a latent point is,
// O(N) per point. Gaussian kernels whose width is the median distance from a training
// point to its k-th nearest neighbour, evaluated as a log-sum-exp about the nearest point
// so a far-away x gets a finite log density instead of ln 0. k = 1 (the model's own
// LogDensity) follows the data closely; a larger k smooths over the gaps between the
// training cycles, so the density does not ripple between them.
#pragma once

#include <Eigen/Core>

namespace jgpm {

class LatentDensity {
 public:
  // Copies the points (N x 3, N > neighbours >= 1).
  explicit LatentDensity(const Eigen::MatrixXd& points, int neighbours = 1);

  double width() const { return width_; }
  // ln p(x), normalised; `gradient` may be null.
  double LogDensity(const Eigen::Vector3d& x, Eigen::Vector3d* gradient) const;
  // ln p(x) without the gradient; `distances2` (N entries) is scratch kept by the caller,
  // so repeated calls allocate nothing.
  double LogDensity(const Eigen::Vector3d& x, Eigen::Ref<Eigen::VectorXd> distances2) const;

  Eigen::MatrixXd points_;
  double width_ = 1.0;
  double log_n_ = 0, log_width_ = 0;  // ln N, ln h
};

}  // namespace jgpm
