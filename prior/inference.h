// Sequence inference with a trained gait model (paper eq. 15, METHOD.md section 4): the
// latent points x_1..x_T whose mean poses best explain an observed pose sequence u_1..u_T,
// some of whose channels may be missing or noisy. It minimises over all T points at once
//
//   E(X) =  sum_t sum_{k observed} (u_tk - f_k(x_t))^2 / (2 s_k^2)     -ln p(u|y) p(y|x, M)
//         - sum_t ln p(x_t|M)                                         latent density
//         + sum_{t>1} |x_t - g(x_{t-1})|^2 / (2 d^2)                   GPDM dynamics
//
// with f the model's mean pose, g its dynamics step (GPDM family only) and
// s_k^2 = (observation_noise * training std of channel k)^2 + (known noise std of k)^2.
// The pose y_t is taken at the mode f(x_t) of p(y|x, M), and the estimate is f(x_t): the
// error then measures how well the model represents the input, not how well it copies it.
// The predictive-variance part of ln p(x|M) is left out: it costs O(N^2) per point where
// everything else is O(N), and the density already keeps x near the learned manifold.
// The dynamics tolerance d is a fraction of the model's mean latent step between
// consecutive training poses, so models with different latent scales are treated alike.
//
// Initialisation: each x_t starts at the latent point of the training pose nearest to
// u_t on the observed channels (nanoflann); then L-BFGS (Ceres) refines all of them.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "prior/gait_model.h"

namespace jgpm {

struct InferenceOptions {
  // s_k of an observed channel, in training standard deviations of that channel.
  double observation_noise = 0.1;
  // d, in mean latent steps between consecutive training poses.
  double dynamics_tolerance = 0.5;
  int max_iterations = 200;  // L-BFGS iterations

  bool Check(std::string* why) const;
};

// What is observed of a pose sequence.
struct PoseObservations {
  Eigen::MatrixXd poses_deg;      // T x D, the model's channels in degrees
  std::vector<bool> observed;     // D flags; empty: every channel observed
  Eigen::VectorXd noise_std_deg;  // D known noise standard deviations; empty: none
};

// E(X) above for one observed sequence; references `model`, which must outlive it.
class SequenceEnergy {
 public:
  SequenceEnergy(const GaitModel& model, const PoseObservations& observations, const InferenceOptions& options);
  // E at the latent points (T x 3); with `gradient`, also dE/dX (T x 3).
  double Evaluate(const Eigen::MatrixXd& latent, Eigen::MatrixXd* gradient) const;

 private:
  const GaitModel& model_;
  Eigen::MatrixXd u_;          // the observations, 0 on unobserved channels
  Eigen::RowVectorXd weight_;  // 1 / s_k^2 on observed channels, 0 elsewhere
  double dynamics_weight_ = 0; // 1 / d^2 for GPDM-family models, else 0
};

struct InferenceResult {
  Eigen::MatrixXd initial_latent;  // T x 3, the nearest training poses' latent points
  Eigen::MatrixXd latent;          // T x 3
  Eigen::MatrixXd poses_deg;       // T x D, f(x_t)
  double initial_objective = 0;
  double final_objective = 0;
  int iterations = 0;
};

// InputError for bad options, observations of the wrong size, non-finite values or no
// observed channel.
InferenceResult InferLatentSequence(const GaitModel& model, const PoseObservations& observations,
                                    const InferenceOptions& options = {});

}  // namespace jgpm
