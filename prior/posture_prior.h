// How a person's posture may differ from the training subjects': a Gaussian prior on a
// per-person offset delta of the gait channels (y_t = f(x_t) + delta, issue #15).
//
// A prior trained on a few people represents their postures, not a stranger's: CMU subject
// 07 holds the neck rolled ~12 degrees and the right upper arm ~30 degrees away from the
// training subjects' mean, which no latent point reproduces (~71 mm mean joint error at
// s = 1, against ~20 mm for new trials of training subjects). A constant offset, estimated
// with the latent sequence, takes that up.
//
// The prior is centred on zero (the training subjects' average posture, which the model
// already represents). Its covariance is the spread of the training subjects' mean postures
// (each subject's mean over its cycles of stride scale 1, the cycles weighted equally),
// the unbiased covariance over subjects, S = sum_s (m_s - m)(m_s - m)^T / (n - 1), shrunk:
//   Sigma = diag(sigma) ((1 - c) I + c R) diag(sigma) + floor_deg^2 I,  sigma_k^2 = S_kk,
// with R the correlations of S and c = correlation_weight. Four or five subjects cannot
// estimate 43 x 43 correlations, so they are kept only in part (c = 0.5): enough that
// a missing channel's offset follows the observed channels it moved with in training
// (the left arm with the right), not so much that three subjects' accidents are taken as
// laws. The floor keeps channels every training subject held alike (S_kk ~ 0) adaptable by
// a few degrees. A MAP offset is the data's mean residual pulled toward zero: per channel,
// by sigma_k^2 / (sigma_k^2 + s_k^2 / T) for T frames of noise s_k, so a whole observed
// cycle is barely shrunk, while what is not observed (or silhouettes cannot show) stays at
// the prior's conditional mean.
//
// From the eigendecomposition Sigma = V Lambda V^T (the floor makes every eigenvalue at
// least floor_deg^2, so both are well conditioned): A = V Lambda^1/2 draws offsets,
// delta = A z with z ~ N(0, I), a step in z being a plausible posture change; and
// W = Lambda^-1/2 V^T whitens them, the prior's energy being 1/2 |W delta|^2.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "prior/training_set.h"

namespace jgpm {

struct PosturePriorOptions {
  double correlation_weight = 0.5;  // c: fraction of the subjects' correlations kept
  double floor_deg = 2.0;           // added in quadrature to each channel's spread (> 0)

  bool Check(std::string* why) const;
};

class PosturePrior {
 public:
  // From the training set's subjects (the part of each gait id before '_'). One subject
  // gives S = 0: the offset is then bounded by the floor alone. InputError for bad options.
  static PosturePrior FromTrainingSet(const TrainingSet& set, const PosturePriorOptions& options = {});
  // From a covariance (D x D, symmetric positive definite). InputError otherwise.
  explicit PosturePrior(const Eigen::MatrixXd& covariance_deg2);

  int NumChannels() const { return static_cast<int>(covariance_.rows()); }
  int NumSubjects() const { return subjects_; }
  const Eigen::MatrixXd& covariance() const { return covariance_; }  // Sigma, degrees^2
  const Eigen::MatrixXd& root() const { return root_; }              // A, A A^T = Sigma
  const Eigen::MatrixXd& whitening() const { return whitening_; }    // W, W^T W = Sigma^-1
  Eigen::VectorXd StdDeg() const { return covariance_.diagonal().cwiseSqrt(); }
  // -ln p(delta) up to a constant: 1/2 |W delta|^2.
  double Energy(const Eigen::VectorXd& offset_deg) const { return 0.5 * (whitening_ * offset_deg).squaredNorm(); }

 private:
  PosturePrior() = default;
  void Factorise(const Eigen::MatrixXd& covariance_deg2);

  Eigen::MatrixXd covariance_, root_, whitening_;
  int subjects_ = 0;
};

}  // namespace jgpm
