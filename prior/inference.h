// Sequence inference with a trained gait model (paper eq. 15, METHOD.md section 4): the
// latent points x_1..x_T whose mean poses best explain an observed pose sequence u_1..u_T,
// some of whose channels may be missing or noisy. It minimises over all T points at once
//
//   E(X) = 1/2 sum_t sum_{k observed} (f_k(x_t) - u_tk)^2 / s_k^2      -ln p(u|y) p(y|x, M)
//        - sum_t ln p(x_t|M)                                           the model's latent prior
//
// with f the model's mean pose and s_k^2 = observation_noise_deg^2 + (known noise std of
// channel k)^2. The pose y_t is taken at the mode f(x_t) of p(y|x, M), and the estimate is
// f(x_t): the error then measures how well the model represents the input, not how well it
// copies it. The noise is the same in every channel: normalising by each channel's training
// spread instead gave channels that barely move in training (neck and head roll) weights
// 100 times the hips', and an unseen subject's posture offset of 11 degrees there (CMU
// subject 07) then pulled whole test poses 30 mm further off.
//
// p(x|M) is each model's own latent prior, as the paper has it ("in GPDM, p(x_t|M) is a
// Gaussian model to predict the next point along the pose manifold"):
//   GPDM family: 1/2 sum_{t>1} |x_t - g(x_{t-1})|^2 / d^2, g the dynamics mean step and d a
//     fraction of the mean latent step between consecutive training poses, so models with
//     different latent scales are treated alike;
//   PCA, GPLVM: a Gaussian fitted to the training latent points (per dimension).
// Every term is a squared residual, so Levenberg-Marquardt (Ceres) solves it: on the test
// split 10 iterations reach the error 200 L-BFGS iterations did (34.6 vs 35.1 mm, ML-JGPM).
// The frames' mean poses and Jacobians are computed in one batch per evaluation.
//
// Initialisation: each x_t starts at the latent point of the training pose nearest to
// u_t on the observed channels (nanoflann).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "prior/gait_model.h"
#include "prior/termination.h"

namespace jgpm {

struct InferenceOptions {
  // s_k of an observed channel, degrees (before adding a known noise).
  double observation_noise_deg = 2.0;
  // d, in mean latent steps between consecutive training poses.
  double dynamics_tolerance = 0.5;
  int max_iterations = 15;  // Levenberg-Marquardt iterations

  bool Check(std::string* why) const;
};

// What is observed of a pose sequence.
struct PoseObservations {
  Eigen::MatrixXd poses_deg;      // T x D, the model's channels in degrees
  std::vector<bool> observed;     // D flags; empty: every channel observed
  Eigen::VectorXd noise_std_deg;  // D known noise standard deviations; empty: none
};

struct InferenceResult {
  Eigen::MatrixXd initial_latent;  // T x 3, the nearest training poses' latent points
  Eigen::MatrixXd latent;          // T x 3
  Eigen::MatrixXd poses_deg;       // T x D, f(x_t)
  double initial_objective = 0;    // E at initial_latent
  double final_objective = 0;
  int iterations = 0;
  // How Levenberg-Marquardt ended. On a numerical failure the latent points are the last
  // ones it could evaluate (the start, if none).
  Termination termination = Termination::kNoConvergence;
  std::string message;             // Ceres's
};

// E(X) for one observed sequence, as a Ceres problem. References `model`, which must
// outlive it. InputError for bad options, observations of the wrong size, non-finite
// observed values or no observed channel.
class SequenceProblem {
 public:
  SequenceProblem(const GaitModel& model, const PoseObservations& observations, const InferenceOptions& options);
  ~SequenceProblem();

  int NumFrames() const;
  // E at `latent` (T x 3); with `gradient`, also dE/dX (T x 3).
  double Evaluate(const Eigen::MatrixXd& latent, Eigen::MatrixXd* gradient);
  // Minimises E from `initial_latent`.
  InferenceResult Solve(const Eigen::MatrixXd& initial_latent);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// The latent point of the training pose nearest to each observed pose (T x 3), on the
// observed channels in training standard deviations.
Eigen::MatrixXd NearestTrainingLatents(const GaitModel& model, const PoseObservations& observations);

// SequenceProblem(...).Solve(NearestTrainingLatents(...)).
InferenceResult InferLatentSequence(const GaitModel& model, const PoseObservations& observations,
                                    const InferenceOptions& options = {});

}  // namespace jgpm
