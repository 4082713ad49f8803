// A transition between two motions (prior/transition.h), end to end on a synthetic walk
// whose every pose is known (prior_test_support.h): a transition between the walk and
// itself (B the same cycle sampled half a frame later) along the straight line stays on
// the walk; pushed far off the line it does not (the test can fail); LI is LSOPA with
// l = 0 on the learned model; bad input is refused.
#include "prior/transition.h"

#include <chrono>
#include <cmath>

#include <gtest/gtest.h>

#include "prior_test_support.h"

namespace jgpm {
namespace {

using test::ExpectInputError;

constexpr double kPi = 3.14159265358979323846;
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
    for (int k = 0; k < kFrames; ++k) poses.row(k) = At(2 * kPi * (k + offset) / kFrames).transpose();
    return poses;
  }
  // RMS over channels (degrees) from the pose to the nearest pose of the walk.
  double Off(const Eigen::VectorXd& pose) const {
    double best = 1e300;
    for (int s = 0; s < 3000; ++s) best = std::min(best, (pose - At(2 * kPi * s / 3000)).squaredNorm());
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
