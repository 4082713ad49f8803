#include "prior/motion/latent_transition.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>
#include <random>
#include <vector>

#include <Eigen/Geometry>

#include "io/base/error.h"

namespace jgpm {
namespace {


void CheckFinite(const Eigen::Vector3d& v, const char* what) {
  if (!v.allFinite()) ThrowInputError("latent transition", std::string(what) + " is not finite");
}

// d = b - a, refused when a and b coincide (no direction to progress along).
Eigen::Vector3d Chord(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  CheckFinite(a, "a (motion A's last latent point)");
  CheckFinite(b, "b (motion B's first latent point)");
  const Eigen::Vector3d d = b - a;
  if (!(d.norm() > 1e-12 * std::max(1.0, a.norm()))) {
    ThrowInputError("latent transition", "a and b coincide: there is no direction to go");
  }
  return d;
}

Eigen::Vector3d OrthogonalPart(const Eigen::Vector3d& v, const Eigen::Vector3d& unit_d) {
  return v - v.dot(unit_d) * unit_d;
}

void CheckFrames(int frames) {
  if (frames < 1) ThrowInputError("latent transition", "frames must be >= 1, got " + std::to_string(frames));
}

// One pose per row of xs, checked: the search must never compare NaN.
Eigen::MatrixXd Evaluate(const MeanPoseFunction& mean_poses, const Eigen::MatrixXd& xs, Eigen::Index dims) {
  Eigen::MatrixXd poses = mean_poses(xs);
  if (poses.rows() != xs.rows() || (dims >= 0 && poses.cols() != dims)) {
    ThrowInputError("latent transition", "the mean-pose function returned " + std::to_string(poses.rows()) + " x " +
                                             std::to_string(poses.cols()) + " for " + std::to_string(xs.rows()) +
                                             " latent points");
  }
  if (!poses.allFinite()) ThrowInputError("latent transition", "the mean-pose function returned a non-finite pose");
  return poses;
}

}  // namespace

bool LatentTransitionOptions::Check(std::string* why) const {
  const char* problem = nullptr;
  if (frames < 1) problem = "frames must be >= 1";
  else if (!(peak_offset >= 0 && std::isfinite(peak_offset))) problem = "peak_offset must be finite and >= 0";
  else if (!(max_angle_deg > 0 && max_angle_deg <= 180)) problem = "max_angle_deg must be in (0, 180]";
  else if (samples < 3) problem = "samples must be >= 3";
  if (problem && why) *why = problem;
  return problem == nullptr;
}

Eigen::Vector3d ReferenceDirection(const Eigen::Vector3d& before_a, const Eigen::Vector3d& a,
                                   const Eigen::Vector3d& b, const Eigen::Vector3d& after_b) {
  CheckFinite(before_a, "the point before a");
  CheckFinite(after_b, "the point after b");
  const Eigen::Vector3d d = Chord(a, b), unit_d = d.normalized();
  // "Too small": under 1% of the velocity's length, or of |d| when the velocity is zero.
  for (const Eigen::Vector3d& velocity : {Eigen::Vector3d(a - before_a), Eigen::Vector3d(after_b - b)}) {
    const Eigen::Vector3d r = OrthogonalPart(velocity, unit_d);
    if (r.norm() > 1e-2 * std::max(velocity.norm(), 1e-6 * d.norm())) return r.normalized();
  }
  Eigen::Index axis;
  unit_d.cwiseAbs().minCoeff(&axis);
  return OrthogonalPart(Eigen::Vector3d::Unit(axis), unit_d).normalized();
}

Eigen::MatrixXd LsopaPath(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& reference,
                          const LatentTransitionOptions& options, const MeanPoseFunction& mean_poses) {
  std::string why;
  if (!options.Check(&why)) ThrowInputError("latent transition options", why);
  const Eigen::Vector3d d = Chord(a, b), unit_d = d.normalized();
  CheckFinite(reference, "the reference direction C");
  const Eigen::Vector3d c = OrthogonalPart(reference, unit_d);
  if (!(c.norm() > 1e-9 * reference.norm())) {
    ThrowInputError("latent transition", "the reference direction C is parallel to b - a");
  }
  // Orthonormal basis (u, w) of the plane orthogonal to d, u along C: x(phi) = centre +
  // radius (cos phi u + sin phi w), |phi| <= theta.
  const Eigen::Vector3d u = c.normalized(), w = unit_d.cross(u);
  const int n = options.frames;
  const double theta = options.max_angle_deg * std::numbers::pi / 180;

  Eigen::MatrixXd path(n, 3);
  Eigen::MatrixXd previous_pose = Evaluate(mean_poses, a.transpose(), -1);
  const Eigen::Index dims = previous_pose.cols();
  for (int i = 1; i <= n; ++i) {
    const double t = static_cast<double>(i) / (n + 1);
    const Eigen::Vector3d centre = a + t * d;
    const double radius = options.peak_offset * d.norm() * std::sin(std::numbers::pi * t);
    auto at = [&](double phi) -> Eigen::Vector3d {
      return centre + radius * (std::cos(phi) * u + std::sin(phi) * w);
    };
    if (radius == 0) {  // the circle is a point
      path.row(i - 1) = centre.transpose();
      previous_pose = Evaluate(mean_poses, centre.transpose(), dims);
      continue;
    }
    // Dense search over [-theta, theta].
    const int k = options.samples;
    Eigen::MatrixXd xs(k, 3);
    std::vector<double> angles(k);
    for (int s = 0; s < k; ++s) {
      angles[s] = -theta + 2 * theta * s / (k - 1);
      xs.row(s) = at(angles[s]).transpose();
    }
    const Eigen::MatrixXd poses = Evaluate(mean_poses, xs, dims);
    const Eigen::VectorXd step = (poses.rowwise() - previous_pose.row(0)).rowwise().squaredNorm();
    Eigen::Index best;
    step.minCoeff(&best);
    // Golden-section search in the samples' bracket around the best one.
    double lo = angles[std::max<Eigen::Index>(best - 1, 0)], hi = angles[std::min<Eigen::Index>(best + 1, k - 1)];
    auto cost = [&](double phi) {
      return (Evaluate(mean_poses, at(phi).transpose(), dims) - previous_pose).squaredNorm();
    };
    const double g = (std::sqrt(5.0) - 1) / 2;
    double x1 = hi - g * (hi - lo), x2 = lo + g * (hi - lo), f1 = cost(x1), f2 = cost(x2);
    for (int iteration = 0; iteration < 80 && hi - lo > 1e-12; ++iteration) {
      if (f1 <= f2) {
        hi = x2, x2 = x1, f2 = f1, x1 = hi - g * (hi - lo), f1 = cost(x1);
      } else {
        lo = x1, x1 = x2, f1 = f2, x2 = lo + g * (hi - lo), f2 = cost(x2);
      }
    }
    double phi = f1 <= f2 ? x1 : x2, best_cost = std::min(f1, f2);
    if (step(best) < best_cost) phi = angles[best];  // a sample at the bracket's edge can still win
    const Eigen::Vector3d x = at(phi);
    path.row(i - 1) = x.transpose();
    previous_pose = Evaluate(mean_poses, x.transpose(), dims);
  }
  return path;
}

Eigen::MatrixXd LinearPath(const Eigen::Vector3d& a, const Eigen::Vector3d& b, int frames) {
  CheckFrames(frames);
  const Eigen::Vector3d d = Chord(a, b);
  Eigen::MatrixXd path(frames, 3);
  for (int i = 1; i <= frames; ++i) path.row(i - 1) = (a + (static_cast<double>(i) / (frames + 1)) * d).transpose();
  return path;
}

Eigen::MatrixXd RandomPath(const Eigen::Vector3d& a, const Eigen::Vector3d& b, int frames, uint64_t seed) {
  CheckFrames(frames);
  const Eigen::Vector3d d = Chord(a, b);
  // 53-bit uniforms from the raw engine: the same points on every standard library.
  std::mt19937_64 engine(seed);
  auto uniform = [&] { return static_cast<double>(engine() >> 11) * 0x1.0p-53; };
  std::vector<Eigen::Vector3d> points(frames);
  for (Eigen::Vector3d& p : points) {
    for (int k = 0; k < 3; ++k) p(k) = a(k) + uniform() * d(k);
  }
  std::vector<double> progress(frames);
  for (int i = 0; i < frames; ++i) progress[i] = (points[i] - a).dot(d);
  std::vector<int> order(frames);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int i, int j) { return progress[i] < progress[j]; });
  Eigen::MatrixXd path(frames, 3);
  for (int i = 0; i < frames; ++i) path.row(i) = points[order[i]].transpose();
  return path;
}

}  // namespace jgpm
