// Transition measures (prior/motion/transition_measures.h) against hand-computed cases on a made-up
// skeleton: the truth itself scores zero; a root shifted by d is d mm off in the world and
// 0 root-aligned, with seam jumps of d x fps; a knee bent by theta moves the ankle and the
// foot's end by 2 r sin(theta / 2); a sliding planted foot skates at the slide's speed;
// power spectra do not see time reversal.
#include "prior/motion/transition_measures.h"

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "io/mocap/asf.h"
#include "test_support.h"

namespace jgpm {
namespace {

using test::ExpectInputError;

constexpr double kUnitMm = 25.4 / 0.45;

struct Fixture {
  Skeleton skeleton = ParseAsf(test::GaitAsfText(), "gait.asf");
  int Channel(const std::string& name) const {
    const std::vector<std::string> names = skeleton.ChannelNames();
    return static_cast<int>(std::find(names.begin(), names.end(), name) - names.begin());
  }
  // 20 frames of a slow walk-like motion: the root moving along z, arms and legs swinging.
  RowMatrixXd Truth() const {
    RowMatrixXd m = RowMatrixXd::Zero(20, skeleton.NumChannels());
    for (int f = 0; f < 20; ++f) {
      m(f, Channel("root.tz")) = 20.0 * f / kUnitMm;
      m(f, Channel("lfemur.rx")) = 25 * std::sin(f * 0.4);
      m(f, Channel("rfemur.rx")) = -25 * std::sin(f * 0.4);
      m(f, Channel("lhumerus.rz")) = 15 * std::cos(f * 0.4);
      m(f, Channel("ltibia.rx")) = 20 + 10 * std::sin(f * 0.3);
    }
    return m;
  }
};

TransitionWindow Window() {
  TransitionWindow w;
  w.first = 6;
  w.frames = 8;
  w.floor_mm = -1e9;  // no foot on the floor unless a test says so
  return w;
}

TEST(TransitionMeasures, TheTruthScoresZero) {
  const Fixture f;
  const RowMatrixXd truth = f.Truth();
  const TransitionMeasures m = MeasureTransition(f.skeleton, truth, truth, Window());
  ASSERT_EQ(m.eq23_mm.size(), 8u);
  for (double v : m.eq23_mm) EXPECT_EQ(v, 0);
  EXPECT_EQ(m.l2p_m, 0);
  EXPECT_EQ(m.l2q, 0);
  EXPECT_EQ(m.npss, 0);
  for (int s = 0; s < 2; ++s) EXPECT_EQ(m.seam_jump_mps[s], m.true_seam_jump_mps[s]);
}

TEST(TransitionMeasures, AShiftedRootIsOffInTheWorldOnly) {
  const Fixture f;
  const RowMatrixXd truth = f.Truth();
  RowMatrixXd estimate = truth;
  const double d_mm = 37;
  estimate.block(6, f.Channel("root.tx"), 8, 1).array() += d_mm / kUnitMm;
  const TransitionWindow w = Window();
  const TransitionMeasures m = MeasureTransition(f.skeleton, truth, estimate, w);
  for (int i = 0; i < 8; ++i) {
    EXPECT_NEAR(m.eq23_mm[i], d_mm, 1e-9);
    EXPECT_NEAR(m.eq23_root_aligned_mm[i], 0, 1e-9);
  }
  EXPECT_NEAR(m.l2p_m, std::sqrt(17.0) * d_mm / 1000, 1e-12);
  EXPECT_NEAR(m.l2q, 0, 1e-12);
  // On a truth of constant velocity (no seam jump of its own): only frame 6 moved at the
  // first seam (frame 5), so the velocity changes by d per frame; at the second (frame
  // 13), frames 12 and 13 moved and 14 did not: again d.
  RowMatrixXd steady = RowMatrixXd::Zero(20, f.skeleton.NumChannels());
  for (int k = 0; k < 20; ++k) steady(k, f.Channel("root.tz")) = 20.0 * k / kUnitMm;
  RowMatrixXd shifted = steady;
  shifted.block(6, f.Channel("root.tx"), 8, 1).array() += d_mm / kUnitMm;
  const TransitionMeasures jumps = MeasureTransition(f.skeleton, steady, shifted, w);
  for (int s = 0; s < 2; ++s) {
    EXPECT_NEAR(jumps.true_seam_jump_mps[s], 0, 1e-9) << s;
    EXPECT_NEAR(jumps.seam_jump_mps[s], d_mm * w.frames_per_second / 1000, 1e-9) << s;
  }
}

// The left knee bent by theta more: the ankle (7 units below the knee) and the foot's end
// (7 below and 2 ahead) turn about the knee's x axis, each by 2 r sin(theta / 2); nothing
// else moves, so the frame's mean over 17 joints is their sum over 17.
TEST(TransitionMeasures, ABentKneeMovesTheAnkleAndFootByTheChord) {
  const Fixture f;
  RowMatrixXd truth = RowMatrixXd::Zero(12, f.skeleton.NumChannels()), estimate = truth;
  const double theta = 30;
  estimate.block(2, f.Channel("ltibia.rx"), 8, 1).array() += theta;
  TransitionWindow w = Window();
  w.first = 2;
  const TransitionMeasures m = MeasureTransition(f.skeleton, truth, estimate, w);
  const double chord = 2 * std::sin(theta / 2 * std::numbers::pi / 180) * kUnitMm;
  const double expected = chord * (7 + std::sqrt(7.0 * 7 + 2 * 2)) / 17;
  for (int i = 0; i < 8; ++i) {
    EXPECT_NEAR(m.eq23_mm[i], expected, 1e-9);
    EXPECT_NEAR(m.eq23_root_aligned_mm[i], expected, 1e-9);
  }
  // Two bones (tibia and foot) turned by theta: |q - q_true| = 2 sin(theta / 4) each.
  EXPECT_NEAR(m.l2q, std::sqrt(2.0) * 2 * std::sin(theta / 4 * std::numbers::pi / 180), 1e-9);
}

TEST(TransitionMeasures, APlantedFootThatSlidesSkates) {
  const Fixture f;
  RowMatrixXd truth = RowMatrixXd::Zero(12, f.skeleton.NumChannels()), estimate = truth;
  for (int k = 0; k < 12; ++k) estimate(k, f.Channel("root.tx")) = 500.0 / 30 * k / kUnitMm;  // 0.5 m/s
  TransitionWindow w = Window();
  w.first = 2;
  w.floor_mm = -1e4;
  w.contact_mm = 2e4;  // every foot is on the floor
  const TransitionMeasures m = MeasureTransition(f.skeleton, truth, estimate, w);
  EXPECT_NEAR(m.foot_skate_mps, 0.5, 1e-9);
  EXPECT_NEAR(m.true_foot_skate_mps, 0, 1e-12);
  w.contact_mm = 0;  // now none is
  EXPECT_EQ(MeasureTransition(f.skeleton, truth, estimate, w).foot_skate_mps, 0);
}

TEST(TransitionMeasures, NpssSeesSpectraNotOrder) {
  const Fixture f;
  const RowMatrixXd truth = f.Truth();
  RowMatrixXd reversed = truth;
  for (int i = 0; i < 8; ++i) reversed.row(6 + i) = truth.row(13 - i);
  const TransitionMeasures r = MeasureTransition(f.skeleton, truth, reversed, Window());
  EXPECT_NEAR(r.npss, 0, 1e-9);          // the same power spectra
  EXPECT_GT(r.eq23_root_aligned_mean_mm, 1);  // though the poses differ
  // Jitter adds power at high frequencies: more jitter, further from the truth's spectra.
  double previous = 0;
  for (const double amplitude : {5.0, 15.0}) {
    RowMatrixXd jittery = truth;
    for (int i = 0; i < 8; ++i) jittery(6 + i, f.Channel("lfemur.rx")) += (i % 2 ? amplitude : -amplitude);
    const double npss = MeasureTransition(f.skeleton, truth, jittery, Window()).npss;
    EXPECT_GT(npss, previous + 1e-4) << amplitude;
    previous = npss;
  }
}

TEST(TransitionMeasures, RefusesWhatDoesNotFit) {
  const Fixture f;
  const RowMatrixXd truth = f.Truth();
  TransitionWindow w = Window();
  w.first = 1;
  ExpectInputError([&] { MeasureTransition(f.skeleton, truth, truth, w); }, {"2 frames before"});
  w = Window();
  w.frames = 13;
  ExpectInputError([&] { MeasureTransition(f.skeleton, truth, truth, w); }, {"2 frames before and after"});
  ExpectInputError([&] { MeasureTransition(f.skeleton, truth, truth.topRows(10), Window()); }, {"as many"});
  RowMatrixXd bad = truth;
  bad(7, 3) = NAN;
  ExpectInputError([&] { MeasureTransition(f.skeleton, truth, bad, Window()); }, {"not finite"});
}

}  // namespace
}  // namespace jgpm
