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
// with R the correlations of S and c = correlation_weight. A few subjects cannot estimate
// 43 x 43 correlations, and how far to trust them (c) and how much any channel may move
// beyond what the subjects show (the floor) depend on the subjects, so with three or more
// subjects both are chosen from a grid by leave-one-subject-out: the pair under which each
// subject's mean posture is most probable given the others' prior (the mean log density).
// This uses the training subjects alone, never test data. On the default split's four
// subjects it picks c = 0 and 3 degrees (correlations of three subjects do not predict the
// fourth); with many subjects it keeps more of them. The correlations let a missing
// channel's offset follow the observed channels it moved with in training; the floor keeps
// channels every training subject held alike (S_kk ~ 0) adaptable. A MAP offset is the
// data's mean residual pulled toward zero: per channel, by sigma_k^2 / (sigma_k^2 + s_k^2 / T)
// for T frames of noise s_k, so a whole observed cycle is barely shrunk, while what is not
// observed (or silhouettes cannot show) stays at the prior's conditional mean.
//
// From the eigendecomposition Sigma = V Lambda V^T (the floor makes every eigenvalue at
// least floor_deg^2, so both are well conditioned): A = V Lambda^1/2 draws offsets,
// delta = A z with z ~ N(0, I), a step in z being a plausible posture change; and
// W = Lambda^-1/2 V^T whitens them, the prior's energy being 1/2 |W delta|^2.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "prior/learning/training_set.h"

namespace jgpm {

struct PosturePriorOptions {
  // Choose c and the floor by leave-one-subject-out (above) when there are >= 3 subjects;
  // otherwise, or when false, the fixed values below.
  bool select = true;
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
  // The c and floor used, and whether leave-one-subject-out chose them.
  double correlation_weight() const { return correlation_weight_; }
  double floor_deg() const { return floor_deg_; }
  bool selected() const { return selected_; }
  // Options that rebuild this prior from the same training set without choosing again (the
  // choice costs ~1.5 ms; callers that build one prior per sequence choose once).
  PosturePriorOptions Chosen() const { return {false, correlation_weight_, floor_deg_}; }
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
  double correlation_weight_ = 0, floor_deg_ = 0;
  bool selected_ = false;
};

// The grids leave-one-subject-out chooses from.
inline constexpr double kPostureCorrelationWeights[] = {0, 0.25, 0.5, 0.75, 1};
inline constexpr double kPostureFloorsDeg[] = {1, 1.5, 2, 3, 4, 6, 8};

// Mean log density of each subject's mean posture (a column of `means`, D x n, n >= 3) under
// the prior made from the other subjects' with c and the floor: the selection's score.
double HeldOutSubjectLogDensity(const Eigen::MatrixXd& means, double correlation_weight, double floor_deg);

}  // namespace jgpm
