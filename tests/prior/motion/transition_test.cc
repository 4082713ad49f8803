// A transition between two motions (prior/motion/transition.h), end to end on a synthetic walk
// whose every pose is known (prior_test_support.h): a transition between the walk and
// itself (B the same cycle sampled half a frame later) along the straight line stays on
// the walk; pushed far off the line it does not (the test can fail); LI is LSOPA with
// l = 0 on the learned model; the latent oracle fits the truth at least as well as any
// training latent point; Algorithm 1's retraining keeps A, the transition and B as one
// sequence and reproduces the transition it was given; bad input is refused.
#include "prior/motion/transition.h"

#include <chrono>
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "prior/prior_test_support.h"

namespace jgpm {
namespace {

using test::ExpectInputError;

constexpr int kFrames = 30;

struct Walk {
  int channels = GaitPoseLayout(ParseAsf(test::Skeleton35().asf, "35.asf"), "35.asf").NumChannels();
  Eigen::VectorXd At(double phase) const {
    Eigen::VectorXd pose(channels);
    for (int c = 0; c < channels; ++c) pose(c) = test::SyntheticWalkAngle(0, phase, c);
    return pose;
  }
  Eigen::MatrixXd Cycle(double offset) const {  // kFrames poses at phases 2 pi (k + offset) / kFrames
    Eigen::MatrixXd poses(kFrames, channels);
    for (int k = 0; k < kFrames; ++k) poses.row(k) = At(2 * std::numbers::pi * (k + offset) / kFrames).transpose();
    return poses;
  }
  // RMS over channels (degrees) from the pose to the nearest pose of the walk.
  double Off(const Eigen::VectorXd& pose) const {
    double best = 1e300;
    for (int s = 0; s < 3000; ++s) best = std::min(best, (pose - At(2 * std::numbers::pi * s / 3000)).squaredNorm());
    return std::sqrt(best / channels);
  }
};

double WorstOff(const Walk& walk, const Transition& t) {
  double worst = 0;
  for (Eigen::Index i = 0; i < t.poses_deg.rows(); ++i) worst = std::max(worst, walk.Off(t.poses_deg.row(i).transpose()));
  return worst;
}

TEST(Transition, BetweenAMotionAndItselfItStaysOnTheMotion) {
  const Walk walk;
  TransitionOptions options;
  options.path.frames = 5;
  options.path.peak_offset = 0;
  const auto start = std::chrono::steady_clock::now();
  const Transition t = MakeTransition(walk.Cycle(0), walk.Cycle(0.5), test::Skeleton35(), options);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  ASSERT_EQ(t.poses_deg.rows(), 5);
  const double on = WorstOff(walk, t);
  std::printf("worst RMS distance from the walk: %.2f degrees (%.2f s with training)\n", on, seconds);
  EXPECT_LT(on, 0.5);  // measured 0.07
  // Far off the line (a bulge of twice |d|) the path leaves the walk.
  options.path.peak_offset = 2;
  const double off = WorstOff(walk, MakeTransition(walk.Cycle(0), walk.Cycle(0.5), test::Skeleton35(), options));
  std::printf("with peak_offset 2: %.2f degrees\n", off);
  EXPECT_GT(off, 2 * on + 1);
}

TEST(Transition, TheLineIsLsopaWithoutOffsetOnTheLearnedModel) {
  const Walk walk;
  TransitionOptions lsopa;
  lsopa.path.peak_offset = 0;
  TransitionOptions line = lsopa;
  line.method = LatentPathMethod::kLinear;
  const Transition a = MakeTransition(walk.Cycle(0), walk.Cycle(0.5), test::Skeleton35(), lsopa);
  const Transition b = MakeTransition(walk.Cycle(0), walk.Cycle(0.5), test::Skeleton35(), line);
  ASSERT_EQ(a.latent.rows(), 15);
  EXPECT_LT((a.latent - b.latent).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_LT((a.poses_deg - b.poses_deg).cwiseAbs().maxCoeff(), 1e-9);
  // The line's ends: a (A's last latent point) and b (B's first), 1/16 and 15/16 of the way.
  const Eigen::MatrixXd& x = a.model->latent();
  const Eigen::RowVectorXd d = x.row(kFrames) - x.row(kFrames - 1);
  EXPECT_LT((a.latent.row(0) - (x.row(kFrames - 1) + d / 16)).norm(), 1e-12);
  TransitionOptions random = lsopa;
  random.method = LatentPathMethod::kRandom;
  EXPECT_GT((MakeTransition(walk.Cycle(0), walk.Cycle(0.5), test::Skeleton35(), random).latent - a.latent).norm(),
            1e-6);
}

// The oracle minimises |f(x) - y| per true frame: no training latent point (where the
// fit starts) and no LSOPA point fits a true frame better. The truth: the walk at phases
// between A's end and B's start, which the model has not seen exactly.
TEST(Transition, TheOracleFitsEachTrueFrameAtLeastAsWellAsAnyTrainingPoint) {
  const Walk walk;
  TransitionOptions options;
  options.path.frames = 6;
  options.method = LatentPathMethod::kOracle;
  Eigen::MatrixXd truth(6, walk.channels);
  for (int i = 0; i < 6; ++i) truth.row(i) = walk.At(2 * std::numbers::pi * (kFrames - 1 + (i + 1) / 7.0 * 1.5) / kFrames).transpose();
  const Transition oracle = MakeTransition(walk.Cycle(0), walk.Cycle(0.5), test::Skeleton35(), options, &truth);
  options.method = LatentPathMethod::kLsopa;
  const Transition lsopa = MakeTransition(walk.Cycle(0), walk.Cycle(0.5), test::Skeleton35(), options);
  const Eigen::MatrixXd training = oracle.model->MeanPoses(oracle.model->latent());
  double oracle_sum = 0, lsopa_sum = 0;
  for (int i = 0; i < 6; ++i) {
    const double fit = (oracle.poses_deg.row(i) - truth.row(i)).norm();
    double best_training = 1e300;
    for (Eigen::Index k = 0; k < training.rows(); ++k) best_training = std::min(best_training, (training.row(k) - truth.row(i)).norm());
    EXPECT_LE(fit, best_training + 1e-9) << "frame " << i;
    oracle_sum += fit;
    lsopa_sum += (lsopa.poses_deg.row(i) - truth.row(i)).norm();
  }
  std::printf("pose distance to the truth, summed over frames: oracle %.2f, LSOPA %.2f degrees\n", oracle_sum, lsopa_sum);
  EXPECT_LT(oracle_sum, lsopa_sum);
  ExpectInputError([&] { MakeTransition(walk.Cycle(0), walk.Cycle(0.5), test::Skeleton35(), [] {
                     TransitionOptions o;
                     o.method = LatentPathMethod::kOracle;
                     return o;
                   }()); },
                   {"latent oracle needs the true transition"});
}

TEST(Transition, RetrainingLearnsATransitionAndBAsOneSequence) {
  const Walk walk;
  TransitionOptions options;
  options.path.frames = 5;
  options.retrain = true;
  const Transition t = MakeTransition(walk.Cycle(0), walk.Cycle(0.5), test::Skeleton35(), options);
  ASSERT_TRUE(t.retrained);
  EXPECT_EQ(t.retrained->latent().rows(), 2 * kFrames + 5);
  EXPECT_EQ(t.retrained->data().set.NumGaits(), 1);  // one sequence: the dynamics cross both seams
  ASSERT_EQ(t.retrained_poses_deg.rows(), 5);
  // The transition is now training data: the new model reproduces it (GP noise apart).
  const double change = (t.retrained_poses_deg - t.poses_deg).cwiseAbs().maxCoeff();
  const double range = t.poses_deg.maxCoeff() - t.poses_deg.minCoeff();
  const TrainingSummary& summary = t.retrained->data().summary;
  std::printf("retraining (%s) changed the transition by %.2g degrees at most (its range %.1f)\n",
              summary.BriefReport().c_str(), change, range);
  EXPECT_TRUE(summary.usable());
  EXPECT_GT(summary.iterations, 0);
  EXPECT_LT(change, 0.05 * range);
  // It started where the first model ended: A's latent points moved little.
  const Eigen::MatrixXd& before = t.model->latent();
  const double moved = (t.retrained->latent().topRows(kFrames) - before.topRows(kFrames)).rowwise().norm().mean();
  const double spread = (before.rowwise() - before.colwise().mean()).rowwise().norm().mean();
  EXPECT_LT(moved, 0.5 * spread);
}

TEST(Transition, RefusesBadInput) {
  const Walk walk;
  ExpectInputError([&] { MakeTransition(walk.Cycle(0), walk.Cycle(0).topRows(20), test::Skeleton35(), {}); },
                   {"same number of frames"});
  Eigen::MatrixXd bad = walk.Cycle(0);
  bad(3, 2) = NAN;
  ExpectInputError([&] { MakeTransition(walk.Cycle(0), bad, test::Skeleton35(), {}); }, {"non-finite"});
  TransitionOptions options;
  options.path.frames = 0;
  ExpectInputError([&] { MakeTransition(walk.Cycle(0), walk.Cycle(0.5), test::Skeleton35(), options); }, {"frames"});
}

}  // namespace
}  // namespace jgpm
