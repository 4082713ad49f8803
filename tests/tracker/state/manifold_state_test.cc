// The JGPM family's particle state (tracker/state/manifold_state.h) at a start without a known
// manifold point: the stride scale is drawn from N(1, start_scale_std) clamped to the
// layers' range (the oracle: the clamped normal's mean and spread, integrated numerically),
// or uniformly over that range with start_scale_std = 0; the phase is uniform.
#include "tracker/state/manifold_state.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "prior/prior_test_support.h"
#include "tracker/state/random.h"

namespace jgpm {
namespace {

struct Moments {
  double mean = 0, std = 0;
};

Moments Sampled(const ManifoldStateModel& model, int n) {
  double sum = 0, sum2 = 0;
  InitialGuess guess;  // no coordinates: spread over the manifold
  std::vector<double> state(model.Dimension());
  for (int i = 0; i < n; ++i) {
    Random random(7, i);
    model.Sample(guess, &random, state.data());
    sum += state[2];
    sum2 += state[2] * state[2];
  }
  const double mean = sum / n;
  return {mean, std::sqrt(sum2 / n - mean * mean)};
}

// min(max(X, lo), hi) for X ~ N(mu, sigma), by the midpoint rule over +-8 sigma.
Moments ClampedNormal(double mu, double sigma, double lo, double hi) {
  const int steps = 200000;
  double m1 = 0, m2 = 0;
  for (int k = 0; k < steps; ++k) {
    const double z = -8 + 16 * (k + 0.5) / steps, w = 16.0 / steps * std::exp(-0.5 * z * z) / std::sqrt(2 * std::numbers::pi);
    const double x = std::clamp(mu + sigma * z, lo, hi);
    m1 += w * x;
    m2 += w * x * x;
  }
  return {m1, std::sqrt(m2 - m1 * m1)};
}

// A multi-layer torus trained briefly on four walks: the layers' range is what matters here.
const GaitModel& Model() {
  static const std::unique_ptr<GaitModel> model = test::TrainOnFirstWalks(ModelKind::kMljgpmTorus, 4, 3);
  return *model;
}

// Sample writes the whole state and reads none of it: a buffer of anything (here left
// uninitialised) gives the state a clean buffer gives. (Its normalisation used to read the
// cadence before writing it; the value read was overwritten, and the clamp compiles to
// branch-free min/max, so no result and not even valgrind showed it: this pins the rule.)
TEST(ManifoldState, SampleReadsNothingOfTheBufferItWrites) {
  const PoseTable table(Model(), {});
  const ManifoldStateModel model(Model(), table);
  const int d = model.Dimension();
  std::vector<double> clean(d, 0.0);
  const std::unique_ptr<double[]> dirty(new double[d]);  // uninitialised on purpose
  InitialGuess guess;
  guess.speed_mm_s = 1300;
  Random a(3, 1), b(3, 1);
  model.Sample(guess, &a, clean.data());
  model.Sample(guess, &b, dirty.get());
  for (int k = 0; k < d; ++k) {
    EXPECT_TRUE(std::isfinite(dirty[k])) << k;
    EXPECT_EQ(dirty[k], clean[k]) << k;
  }
}

// The dynamics without noise.
ManifoldDynamics Quiet() {
  ManifoldDynamics quiet;
  quiet.phase_noise = quiet.cadence_noise = quiet.gait_noise = quiet.scale_noise = quiet.heading_noise_deg = 0;
  quiet.turn_noise_deg = quiet.root_noise_mm = quiet.size_noise = quiet.width_noise = 0;
  return quiet;
}

// One frame of the dynamics without noise, by hand: the phase advances by cadence x dt,
// the root by the stride (for the gait point and stride scale, times the size) per cycle
// along the heading (0: +z), everything else stays; the phase wraps.
TEST(ManifoldState, PredictWithoutNoiseIsTheWalkByHand) {
  const PoseTable table(Model(), {});
  const ManifoldDynamics quiet = Quiet();
  const ManifoldStateModel model(Model(), table, quiet);
  const double gait = 0.5 * (table.lo()[1] + table.hi()[1]), heading = 30 * std::numbers::pi / 180;
  double s[9] = {0.9, gait, 1.0, 100, -200, heading, 1.2, 1.1, 1.05};
  const double stride = table.StrideMm(gait, 1.0) * 1.1;  // mm per cycle at this size
  Random random(1);
  model.Predict(0.2, &random, s);
  EXPECT_NEAR(s[0], 0.9 + 1.2 * 0.2 - 1, 1e-12);  // wrapped
  EXPECT_NEAR(s[3], 100 + stride * 1.2 * 0.2 * std::sin(heading), 1e-9);
  EXPECT_NEAR(s[4], -200 + stride * 1.2 * 0.2 * std::cos(heading), 1e-9);
  EXPECT_DOUBLE_EQ(s[1], gait);
  EXPECT_DOUBLE_EQ(s[2], 1.0);
  EXPECT_DOUBLE_EQ(s[5], heading);
  EXPECT_DOUBLE_EQ(s[6], 1.2);
  EXPECT_DOUBLE_EQ(s[7], 1.1);
  EXPECT_DOUBLE_EQ(s[8], 1.05);
  EXPECT_GT(stride, 500);  // a walker's stride, not a shuffle
}

// The same walk backwards, by hand: a negative cadence runs the phase back and moves the
// root against the heading by the same stride per cycle. Normalising keeps the cadence's
// sign and clamps its size to [min_cadence, max_cadence] either way (a clamp to the
// positive range turned every backward walker forwards).
TEST(ManifoldState, ANegativeCadenceWalksBackwards) {
  const PoseTable table(Model(), {});
  const ManifoldDynamics quiet = Quiet();
  const ManifoldStateModel model(Model(), table, quiet);
  const double gait = 0.5 * (table.lo()[1] + table.hi()[1]), heading = -50 * std::numbers::pi / 180;
  double s[9] = {0.1, gait, 1.0, 100, -200, heading, -0.8, 1.0, 1.0};
  const double stride = table.StrideMm(gait, 1.0);
  Random random(1);
  model.Predict(0.25, &random, s);
  EXPECT_NEAR(s[0], 0.1 - 0.8 * 0.25 + 1, 1e-12);  // wrapped
  EXPECT_NEAR(s[3], 100 - stride * 0.8 * 0.25 * std::sin(heading), 1e-9);
  EXPECT_NEAR(s[4], -200 - stride * 0.8 * 0.25 * std::cos(heading), 1e-9);
  EXPECT_DOUBLE_EQ(s[6], -0.8);
  for (const double cadence : {-0.1, -3.0, 0.1, 3.0}) {
    s[6] = cadence;
    model.Normalise(s);
    EXPECT_DOUBLE_EQ(s[6], std::copysign(std::clamp(std::abs(cadence), quiet.min_cadence, quiet.max_cadence), cadence))
        << cadence;
  }
}

// The pace (the speed the tracker's estimates go) sets the cadence, by hand. Slower than
// stop_speed_mm_s, all the way (share 1): the noiseless walk then covers exactly that
// speed along its heading, forwards or backwards as before; a share moves it that part of
// the way; standing still takes it to min_cadence, its sign kept (a walker who stops keeps
// the way they were going). Faster, the cadence is only kept at walking_min_cadence or more,
// unless asked to cover the speed.
TEST(ManifoldState, ThePaceSetsTheCadenceThatCoversAStop) {
  const PoseTable table(Model(), {});
  const ManifoldDynamics quiet = Quiet();
  const ManifoldStateModel model(Model(), table, quiet);
  const double gait = 0.5 * (table.lo()[1] + table.hi()[1]), heading = 20 * std::numbers::pi / 180;
  const double stride = table.StrideMm(gait, 1.1) * 0.9, slow = 0.8 * quiet.stop_speed_mm_s;
  ASSERT_GT(slow / stride, quiet.min_cadence);
  for (const double cadence : {1.2, -0.8}) {
    double s[9] = {0.3, gait, 1.1, 0, 0, heading, cadence, 0.9, 1.0};
    model.Pace(slow, 1.0, s);
    EXPECT_NEAR(s[6], std::copysign(slow / stride, cadence), 1e-12);
    Random random(1);
    model.Predict(0.5, &random, s);
    EXPECT_NEAR(std::hypot(s[3], s[4]), 0.5 * slow, 1e-9);  // for half a second
    EXPECT_NEAR(std::atan2(s[3], s[4]), cadence > 0 ? heading : heading - std::numbers::pi, 1e-9);
    s[6] = cadence;
    model.Pace(slow, 0.25, s);
    EXPECT_NEAR(s[6], cadence + 0.25 * (std::copysign(slow / stride, cadence) - cadence), 1e-12);
    model.Pace(0, 1.0, s);
    EXPECT_DOUBLE_EQ(s[6], std::copysign(quiet.min_cadence, cadence));
    // Walking on: back to a walker's cadence, a share at a time; one above it is kept.
    model.Pace(1000, 0.25, s);
    EXPECT_NEAR(s[6], std::copysign(quiet.min_cadence + 0.25 * (quiet.walking_min_cadence - quiet.min_cadence), cadence),
                1e-12);
    s[6] = cadence;
    model.Pace(1000, 1.0, s);
    EXPECT_DOUBLE_EQ(s[6], cadence);
    // Covering it whatever it is (a prediction's: no silhouettes to set the cadence): the
    // noiseless walk goes 1 m/s.
    model.Pace(1000, 1.0, s, /*cover=*/true);
    EXPECT_NEAR(s[6], std::copysign(1000 / stride, cadence), 1e-12);
    s[3] = s[4] = 0;
    model.Predict(0.5, &random, s);
    EXPECT_NEAR(std::hypot(s[3], s[4]), 500, 1e-9);
  }
}

TEST(ManifoldState, AStartDrawsTheStrideScaleNearTheRecordedStrides) {
  const GaitModel* model = &Model();
  const PoseTable table(*model, {});
  const double lo = table.lo()[2], hi = table.hi()[2];
  ASSERT_LT(lo, 1);
  ASSERT_GT(hi, 1);
  const int n = 40000;

  ManifoldDynamics dynamics;
  const Moments normal = Sampled(ManifoldStateModel(*model, table, dynamics), n);
  const Moments expected = ClampedNormal(1, dynamics.start_scale_std, lo, hi);
  std::printf("scale %.3f +- %.3f, expected %.3f +- %.3f (range %.2f-%.2f)\n", normal.mean, normal.std, expected.mean,
              expected.std, lo, hi);
  EXPECT_NEAR(normal.mean, expected.mean, 4 * expected.std / std::sqrt(n));
  EXPECT_NEAR(normal.std, expected.std, 0.02 * expected.std);

  dynamics.start_scale_std = 0;  // uniform over the range
  const Moments uniform = Sampled(ManifoldStateModel(*model, table, dynamics), n);
  const double range = hi - lo;
  EXPECT_NEAR(uniform.mean, (lo + hi) / 2, 4 * range / std::sqrt(12.0 * n));
  EXPECT_NEAR(uniform.std, range / std::sqrt(12.0), 0.02 * range / std::sqrt(12.0));
}

}  // namespace
}  // namespace jgpm
