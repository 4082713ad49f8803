// The tracker's per-person posture offset against its definition (tracker/state/posture_state.h),
// written here in the other form of the Gaussian posterior mean,
//   delta = Sigma (Sigma + r^2 / n I)^-1 (s / n),
// with s the (decayed) sum of the deviations and n their count, both worked out by hand
// for each sequence: a whole-sequence mean during the first frames, a window after.
#include "tracker/state/posture_state.h"

#include <cmath>

#include <Eigen/Cholesky>
#include <gtest/gtest.h>

#include "test_support.h"

namespace jgpm {
namespace {

constexpr int kChannels = 6;

// Channels 0 and 3 vary together in the training subjects; 1 and 4 hardly vary.
Eigen::MatrixXd Covariance() {
  Eigen::VectorXd std(kChannels);
  std << 10, 1, 4, 8, 1, 6;
  Eigen::MatrixXd c = std.asDiagonal() * Eigen::MatrixXd::Identity(kChannels, kChannels) * std.asDiagonal();
  c(0, 3) = c(3, 0) = 0.7 * 10 * 8;
  return c;
}

Eigen::VectorXd Expected(const Eigen::VectorXd& sum, double n, double r) {
  const Eigen::MatrixXd sigma = Covariance();
  const Eigen::MatrixXd m = sigma + (r * r / n) * Eigen::MatrixXd::Identity(kChannels, kChannels);
  return sigma * m.ldlt().solve(sum / n);
}

TEST(PostureState, IsThePosteriorMeanOfTheFramesDeviations) {
  PostureStateOptions options;
  options.frames = 10;
  options.frame_deg = 5;
  PostureState state(PosturePrior(Covariance()), options);
  EXPECT_EQ(state.offset(), Eigen::VectorXd::Zero(kChannels));
  Eigen::VectorXd d1(kChannels), d2(kChannels);
  d1 << 12, 6, -3, 0, 0, 5;  // channels 3 and 4 stay where the search started (0)
  d2 << -4, 2, 6, 0, 0, 1;
  // The first frames: their plain sum.
  Eigen::VectorXd sum = Eigen::VectorXd::Zero(kChannels);
  for (int f = 1; f <= 10; ++f) {
    const Eigen::VectorXd& d = f % 3 ? d1 : d2;
    state.Add(d);
    sum += d;
    EXPECT_EQ(state.frames(), f);
    ASSERT_LT((state.offset() - Expected(sum, f, 5)).cwiseAbs().maxCoeff(), 1e-9) << f;
  }
  // The window: the sum decays by 1 - 1/10 per frame, n stays 10.
  for (int f = 0; f < 25; ++f) {
    state.Add(d2);
    sum = 0.9 * sum + d2;
    EXPECT_EQ(state.frames(), 10);
    ASSERT_LT((state.offset() - Expected(sum, 10, 5)).cwiseAbs().maxCoeff(), 1e-9) << f;
  }
  // What the frames show is shrunk little where subjects differ widely (channel 0: by
  // r^2/n against sigma^2, 2.5 vs 100), much where they hardly differ (channel 1: 2.5 vs 1);
  // channel 3, left at 0 by every frame, still follows channel 0 through their
  // correlation; channel 4 stays 0.
  const Eigen::VectorXd& delta = state.offset();
  EXPECT_GT(delta[0] / sum[0] * 10, 0.9);
  EXPECT_LT(delta[1] / sum[1] * 10, 0.4);
  EXPECT_GT(delta[3] * delta[0], 0);
  EXPECT_LT(std::abs(delta[3]), std::abs(delta[0]));
  EXPECT_NEAR(delta[4], 0, 1e-12);
  state.Reset();
  EXPECT_EQ(state.frames(), 0);
  EXPECT_EQ(state.offset(), Eigen::VectorXd::Zero(kChannels));
}

TEST(PostureState, BadOptions) {
  PostureStateOptions options;
  options.frames = 0;
  test::ExpectInputError([&] { PostureState(PosturePrior(Covariance()), options); }, {"frames must be >= 1"});
  options = {};
  options.frame_deg = -1;
  test::ExpectInputError([&] { PostureState(PosturePrior(Covariance()), options); }, {"frame_deg"});
}

}  // namespace
}  // namespace jgpm
