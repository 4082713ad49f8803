// A transition between two motions (issue #16; METHOD.md section 5): one GPDM learned on
// motion A and motion B as two open dynamics sequences (the project's trainer, PCA start,
// its numerics), then N latent points from A's last latent point a to B's first b by one
// of the latent path methods of prior/motion/latent_transition.h (LSOPA, or the LI and RI
// baselines), mapped to poses by the GP mean. C is taken from the learned latent points:
// A's last velocity (ReferenceDirection).
//
// Poses are gait channels (io/gait/gait_pose.h, degrees) of one skeleton; A and B must have
// the same number of frames, since the training set holds sequences of one length (the
// evaluation cuts 45 frames on each side).
//
// The latent oracle (kOracle, for evaluation only: it needs the true transition): for each
// true frame, the latent point whose GP mean pose fits it best (prior/model/inference.h with the
// dynamics term switched off, from the nearest training pose): the floor any latent path
// of this GPDM can reach.
//
// Algorithm 1's retraining (`retrain`): the GPDM is trained again on [A; transition; B] as
// one sequence, from [X_A; X_transition; X_B] and the hyper-parameters learnt on [A; B].
// It updates the model, not the transition already produced; `retrained_poses_deg` is the
// new model's mean pose at its own transition latent points, which shows what it changed.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include <Eigen/Core>

#include "prior/model/gait_model.h"
#include "prior/model/train.h"
#include "prior/motion/latent_transition.h"

namespace jgpm {

enum class LatentPathMethod { kLsopa, kLinear, kRandom, kOracle };

struct TransitionOptions {
  LatentPathMethod method = LatentPathMethod::kLsopa;
  LatentTransitionOptions path;  // N (frames), l and theta (LSOPA only)
  uint64_t seed = 1;             // RI's points
  int max_iterations = 300;      // the GPDM's L-BFGS iterations
  int threads = 0;               // linear-algebra threads while training (0: OpenBLAS's default)
  bool retrain = false;          // Algorithm 1's last step
};

struct Transition {
  std::unique_ptr<GaitModel> model;  // the GPDM on [A; B]
  Eigen::MatrixXd latent;            // N x 3
  Eigen::MatrixXd poses_deg;         // N x D
  // With `retrain`: the GPDM on [A; transition; B], its latent points of the transition and
  // their mean poses.
  std::unique_ptr<GaitModel> retrained;
  Eigen::MatrixXd retrained_latent;
  Eigen::MatrixXd retrained_poses_deg;
};

// `a_deg`, `b_deg`: T x D gait poses of A and B (equal T >= 3); `skeleton` names the ASF
// whose gait channels they are; `truth_deg` (N x D), the true transition, only for
// kOracle. InputError for unequal or non-finite motions, bad options, A's and B's latent
// points coinciding, or kOracle without the truth.
Transition MakeTransition(const Eigen::MatrixXd& a_deg, const Eigen::MatrixXd& b_deg,
                          const ReferenceSkeleton& skeleton, const TransitionOptions& options,
                          const Eigen::MatrixXd* truth_deg = nullptr);

}  // namespace jgpm
