// A transition between two motions (issue #16; METHOD.md section 5): one GPDM learned on
// motion A and motion B as two open dynamics sequences (the project's trainer, PCA start,
// its numerics), then N latent points from A's last latent point a to B's first b by one
// of the latent path methods of prior/latent_transition.h (LSOPA, or the LI and RI
// baselines), mapped to poses by the GP mean. C is taken from the learned latent points:
// A's last velocity (ReferenceDirection).
//
// Poses are gait channels (io/gait_pose.h, degrees) of one skeleton; A and B must have
// the same number of frames, since the training set holds sequences of one length (the
// evaluation cuts 45 frames on each side).
//
// Not yet here: Algorithm 1's retraining of the GPDM on [A; transition; B], which updates
// the model for later transitions but not the transition already produced.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include <Eigen/Core>

#include "prior/gait_model.h"
#include "prior/latent_transition.h"
#include "prior/train.h"

namespace jgpm {

enum class LatentPathMethod { kLsopa, kLinear, kRandom };

struct TransitionOptions {
  LatentPathMethod method = LatentPathMethod::kLsopa;
  LatentTransitionOptions path;  // N (frames), l and theta (LSOPA only)
  uint64_t seed = 1;             // RI's points
  int max_iterations = 300;      // the GPDM's L-BFGS iterations
  int threads = 0;               // linear-algebra threads while training (0: OpenBLAS's default)
};

struct Transition {
  std::unique_ptr<GaitModel> model;  // the GPDM on [A; B]
  Eigen::MatrixXd latent;            // N x 3
  Eigen::MatrixXd poses_deg;         // N x D
};

// `a_deg`, `b_deg`: T x D gait poses of A and B (equal T >= 3); `skeleton` names the ASF
// whose gait channels they are. InputError for unequal or non-finite motions, bad options,
// or A's and B's latent points coinciding.
Transition MakeTransition(const Eigen::MatrixXd& a_deg, const Eigen::MatrixXd& b_deg,
                          const ReferenceSkeleton& skeleton, const TransitionOptions& options);

}  // namespace jgpm
