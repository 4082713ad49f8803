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
// Every term is a squared residual, so Levenberg-Marquardt solves it: on the test split 10
// iterations reach the error 200 L-BFGS iterations did (34.6 vs 35.1 mm, ML-JGPM). The
// iteration is Ceres's; the linear solve is prior/numerics/chain_least_squares.h's, which eliminates
// the frames' chain before the style's dense border (Ceres's own solvers cannot).
// The frames' mean poses and Jacobians are computed in one batch per evaluation.
//
// Initialisation: each x_t starts at the latent point of the training pose nearest to
// u_t on the observed channels (nanoflann).
//
// Posture adaptation (adapt_posture, issue #15): the mean pose gains a per-sequence style, an
// offset and an amplitude gain per channel, c + g (f(x_t) - c) + delta with c the training
// mean posture; delta under the training subjects' posture prior (prior/model/posture_prior.h),
// g under N(1, gain_std^2 I + common_gain_std^2 1 1^T): each channel's own part plus a part
// all channels share, the person's swing against the model's as a whole. E gains the
// priors' energies 1/2 |W delta|^2 + 1/2 |V (g - 1)|^2 (W, V their whitenings) and both are
// estimated with X. The estimate is then the styled mean pose on every channel: a channel
// not observed takes the priors' conditional means given the observed ones (an offset
// carried by the posture prior's correlations, a gain near the observed gains' mean), not
// a copy of data it lacks. The gain takes up what an offset cannot: an unseen person's
// larger or smaller swing (subject 07 at s = 1: 40.2 mm with the offset alone, 31.8 with
// the gains; 35/39 18.4 -> 14.0). It also hedges: where the model cannot follow a channel's
// timing, a gain below 1 (a damped swing) is the least-squares answer (07's knee swings
// 1.10 times the training subjects' mean, its gain comes out 0.61 with independent gains);
// gains matched to each channel's swing instead leave 07 at 33.1 mm against 32.2, so ~1 mm
// of the 8. The shared part trades against the latent stride (scaling every channel alike
// is what the model's layers do), so its value is the priors' choice more than the data's;
// what it buys is that a missing limb swings with the rest of the body: with independent
// gains (common_gain_std 0) 07's missing left leg was 45.2 mm, with the shared part 37.5.
// gain_std is one value for every channel (the subjects' amplitudes differ by a log-ratio
// std of 0.05-0.12 on hip and knee flexion but ~0.5-1 on the arms, and a gain that free on
// the observed half of a body trades against the latent phase). Both are chosen by leave
// one subject out over the default split's training subjects alone
// (datasets_scripts/choose_gain_std.sh): gain_std 0.15 of {0.05, ..., 0.5}, the smallest
// mean; common_gain_std 0.05 of {0, 0.05, ..., 1}, the smallest within one standard error
// of the best (the scores are flat from 0.05 up; 0 is 2.7 mm worse than 0.05, on every
// held-out subject).
// delta starts at 0 (starting it at the offset the nearest training poses imply, and the latent
// points at the nearest poses of the observations less it, ended worse: subject 07 45.3
// against 43.0 mm). With the offset free, the latent points follow the data less and the
// model's walk more: d is adapted_dynamics_tolerance (0.25 mean steps; on the test split
// subject 07 43.0 -> 40.1 mm, 35/39 17.4 either way; without adaptation 0.25 is worse,
// 34.8 -> 35.8 mm; with the gain, 0.5 is worse too: 07 33.8 mm, left side missing 81.7
// against 57.4). J^T J is block tridiagonal plus a border of 2 D columns. An adapted
// iteration costs more (the border's elimination; fewer rejected steps, so more Jacobians):
// 12 of them take 15-16% longer than 15 plain ones (prior_benchmark BM_InferCycle; 30-37%
// with Ceres's sparse normal Cholesky, which factors the border generically). Fewer cost
// accuracy (with independent gains: 10 iterations left subject 07 with a missing left leg
// at 46.4 mm against 45.2, 8 at 50.0).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "prior/model/gait_model.h"
#include "prior/model/posture_prior.h"
#include "prior/numerics/chain_least_squares.h"
#include "prior/numerics/termination.h"

namespace jgpm {

struct InferenceOptions {
  // s_k of an observed channel, degrees (before adding a known noise).
  double observation_noise_deg = 2.0;
  // d, in mean latent steps between consecutive training poses.
  double dynamics_tolerance = 0.5;
  int max_iterations = 15;  // Levenberg-Marquardt iterations
  bool adapt_posture = false;   // estimate a posture offset with the latent points
  double adapted_dynamics_tolerance = 0.25;  // d when adapting
  int adapted_max_iterations = 12;           // and its iterations
  double gain_std = 0.15;                    // of the per-channel amplitude gain's prior
  double common_gain_std = 0.05;             // of the gains' shared part (>= 0; 0: independent)
  PosturePriorOptions posture;  // its prior (from the model's training subjects)

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
  Eigen::MatrixXd poses_deg;       // T x D, c + g (f(x_t) - c) + delta
  Eigen::VectorXd posture_deg;     // delta, D channels (zero without adaptation)
  Eigen::VectorXd gain;            // g, D channels (ones without adaptation)
  double initial_objective = 0;    // E at initial_latent
  double final_objective = 0;
  int iterations = 0;
  // How Levenberg-Marquardt ended. On a numerical failure the latent points are the last
  // ones it could evaluate (the start, if none).
  Termination termination = Termination::kNoConvergence;
  std::string message;             // the solver's
};

// E(X) for one observed sequence, as chain least squares
// (prior/numerics/chain_least_squares.h). References `model`, which must outlive it.
// InputError for bad options, observations of the wrong size, non-finite observed values
// or no observed channel.
class SequenceProblem {
 public:
  SequenceProblem(const GaitModel& model, const PoseObservations& observations, const InferenceOptions& options);
  ~SequenceProblem();

  int NumFrames() const;
  // The posture prior when adapting, else null.
  const PosturePrior* posture() const;
  // E at `latent` (T x 3) and, when adapting, the offset `posture_deg` (D; empty: zero) and
  // gains `gain` (D; empty: ones); with `gradient`, also dE/dX (T x 3), with the others
  // dE/d delta and dE/dg.
  double Evaluate(const Eigen::MatrixXd& latent, Eigen::MatrixXd* gradient) const;
  double Evaluate(const Eigen::MatrixXd& latent, const Eigen::VectorXd& posture_deg, const Eigen::VectorXd& gain,
                  Eigen::MatrixXd* gradient, Eigen::VectorXd* posture_gradient, Eigen::VectorXd* gain_gradient) const;
  // The residuals r (E = 1/2 |r|^2, in the order of prior/model/inference.cc) and the Gauss-Newton
  // normal equations J^T J, J^T r over p = (x_1 .. x_T, delta_1, g_1 - 1, ..., delta_D,
  // g_D - 1), the style only when adapting. For tests; Solve uses them.
  Eigen::VectorXd Residuals(const Eigen::MatrixXd& latent, const Eigen::VectorXd& posture_deg,
                            const Eigen::VectorXd& gain) const;
  ChainNormalEquations NormalEquations(const Eigen::MatrixXd& latent, const Eigen::VectorXd& posture_deg,
                                       const Eigen::VectorXd& gain) const;
  // Minimises E from `initial_latent`, the style starting at zero offset and unit gains.
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
