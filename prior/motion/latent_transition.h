// Latent paths between two motions (issue #16; METHOD.md section 5, the LSOPA paper's
// eqs. 19-22): N latent points between a (motion A's last latent point) and b (motion B's
// first), d = b - a, each found after the one before, x_0 = a, by minimising the pose step
// |f(x_i) - f(x_{i-1})| (f: the model's mean pose) under three constraints:
//   progress along d:        (x_i - a)^T d / |d|^2 = i / (N + 1)                 (eq. 19)
//   distance from line a-b:  |r_i| = l(i) |d| / (N + 1)                           (eq. 20)
//   direction of r_i:        angle(r_i, C) <= theta(i), C orthogonal to d         (eq. 21)
// with r_i the part of x_i - a orthogonal to d. In a 3-D latent space this leaves one free
// angle per point: x_i lies on a circle of radius l(i)|d|/(N+1) about a + i d/(N+1), in
// the plane orthogonal to d, within theta(i) of C. It is solved exactly: a dense search over
// the allowed arc, then golden-section refinement around the best sample (the constraints
// hold by construction, to round-off).
//
// What the paper leaves open, and the choices here (to be tuned on the tuning events of
// datasets_scripts/transitions.txt, never on the reported ones):
// - l(i) = peak_offset (N + 1) sin(pi i / (N + 1)): a bump, zero at both ends so the path
//   leaves a and reaches b along d's line (no sideways jump at either seam), at most
//   peak_offset |d| from the line half-way. The sine is the smoothest bump with one
//   parameter; peak_offset = 0 is the straight line (the LI baseline).
// - theta(i) = max_angle_deg for every i: the path may turn about d by that much either
//   side of C, no more, so it cannot wander to the far side of the line.
// - C: motion A's last latent velocity, its part orthogonal to d (ReferenceDirection): the
//   transition leaves A bending the way A was moving, which keeps the velocity continuous
//   at the first seam; when A moved along d, B's first velocity is used instead.
// - Tuned on the three tuning events (`jgpm eval --suite transitions --methods lsopa
//   --peak-offset P --max-angle T`, N = 5, 15, 30, shifts -4/0/+4, 26 cases; mean eq. 23,
//   mm): the line (P = 0) 128.3; the first guess P = 0.25, T = 60 127.6; P 0.05/0.1/0.15/
//   0.2/0.3 at T = 5: 125.4/123.3/122.2/122.3/126.6; at P = 0.15, T 5/15/30/60: 122.2/122.4/
//   123.2/124.9; P = 0.5 and 1 worse at every T (146-194). So: a small bend toward C, and
//   the narrower the angle the better, i.e. the pose-step minimisation's freedom costs
//   accuracy. Chosen: P = 0.15, T = 15 (0.2 mm from the best, which is within the noise,
//   and leaves the paper's objective some room).
#pragma once

#include <cstdint>
#include <functional>
#include <string>

#include <Eigen/Core>

namespace jgpm {

// Mean poses of the rows of xs (K x 3) as the rows of a K x D matrix.
using MeanPoseFunction = std::function<Eigen::MatrixXd(const Eigen::MatrixXd& xs)>;

struct LatentTransitionOptions {
  int frames = 15;             // N, points strictly between a and b
  double peak_offset = 0.15;   // l's height: the largest distance from line a-b, over |d|
  double max_angle_deg = 15;   // theta, in (0, 180]
  int samples = 181;           // dense search over the allowed arc (>= 3)

  bool Check(std::string* why) const;
};

// The part of a's last latent velocity (a - before_a) orthogonal to d = b - a, unit length;
// when that is too small (A moved along d), the part of B's first velocity (after_b - b)
// orthogonal to d; when that is too, the unit axis least aligned with d, made orthogonal.
// InputError when a == b or an input is not finite.
Eigen::Vector3d ReferenceDirection(const Eigen::Vector3d& before_a, const Eigen::Vector3d& a,
                                   const Eigen::Vector3d& b, const Eigen::Vector3d& after_b);

// LSOPA: the N x 3 latent points (rows) between a and b, as above. `reference` is C (any
// part of it along d is removed). InputError for bad options, a == b, a reference parallel
// to d, non-finite inputs, or a mean-pose function returning the wrong shape or non-finite
// poses.
Eigen::MatrixXd LsopaPath(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& reference,
                          const LatentTransitionOptions& options, const MeanPoseFunction& mean_poses);

// LI: N points evenly spaced on the segment a-b (LSOPA with peak_offset = 0).
Eigen::MatrixXd LinearPath(const Eigen::Vector3d& a, const Eigen::Vector3d& b, int frames);

// RI: N points drawn uniformly in the axis-aligned box spanned by a and b, ordered by their
// progress along d; the same seed gives the same points.
Eigen::MatrixXd RandomPath(const Eigen::Vector3d& a, const Eigen::Vector3d& b, int frames, uint64_t seed);

}  // namespace jgpm
