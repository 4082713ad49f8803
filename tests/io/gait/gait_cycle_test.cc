#include "io/gait/gait_cycle.h"

#include <cmath>
#include <numbers>
#include <random>

#include <gtest/gtest.h>

#include "io/base/text_reader.h"
#include "io/mocap/amc.h"
#include "io/mocap/asf.h"
#include "test_support.h"

namespace jgpm {
namespace {


class GaitCycleTest : public testing::Test {
 protected:
  GaitCycleTest()
      : skeleton_(ReadAsf(test::CmuRoot() / "subjects/07/07.asf")), layout_(skeleton_, "07.asf") {}

  int Channel(const std::string& name) const {
    const auto names = skeleton_.ChannelNames();
    return static_cast<int>(std::find(names.begin(), names.end(), name) - names.begin());
  }
  int PoseChannel(const std::string& name) const {
    const auto& names = layout_.channel_names();
    return static_cast<int>(std::find(names.begin(), names.end(), name) - names.begin());
  }

  // A synthetic walk: thighs swing +/-30 degrees in antiphase with `period` frames, and
  // lowerback.ry swings around 175 degrees, crossing +/-180 (stored wrapped, as files do).
  Motion SyntheticWalk(int frames, double period) const {
    Motion m;
    m.values = RowMatrixXd::Zero(frames, skeleton_.NumChannels());
    for (int t = 0; t < frames; ++t) {
      const double phase = 2 * std::numbers::pi * t / period;
      m.values(t, Channel("lfemur.rx")) = 30 * std::sin(phase);
      m.values(t, Channel("rfemur.rx")) = -30 * std::sin(phase);
      m.values(t, Channel("lowerback.ry")) = WrapDegrees(175 + 10 * std::sin(phase));
    }
    return m;
  }

  Skeleton skeleton_;
  GaitPoseLayout layout_;
};

TEST_F(GaitCycleTest, FindsTheKnownPeriodAndPhase) {
  const Motion m = SyntheticWalk(400, 130);
  const GaitCycle c = ExtractGaitCycle(layout_, m);
  ASSERT_TRUE(c.clean) << c.problem;
  EXPECT_NEAR(c.period_frames, 130, 1);
  EXPECT_NEAR(c.LengthFrames(), 130, 1);
  // Starts at a maximum of lfemur.rx - rfemur.rx: t = 130/4 + 130k (frames numbered from 1).
  const double start_t = c.start_frame - 1;
  EXPECT_NEAR(std::remainder(start_t - 32.5, 130.0), 0, 1.0);
  EXPECT_GT(c.periodicity, 0.99);
  EXPECT_LT(c.closure_deg, 0.5);
  EXPECT_NEAR(c.heading_deg, 0, 1e-9);
  ASSERT_EQ(c.poses.rows(), 30);
  ASSERT_EQ(c.poses.cols(), 43);
  // Resampled poses follow the sine; pose k is at start + k * length / 30.
  for (int k = 0; k < 30; ++k) {
    const double t = start_t + k * c.LengthFrames() / 30.0;
    EXPECT_NEAR(c.poses(k, PoseChannel("lfemur.rx")), 30 * std::sin(2 * std::numbers::pi * t / 130), 0.05) << k;
  }
}

TEST_F(GaitCycleTest, AnglesCrossingPlusMinus180DoNotJump) {
  const GaitCycle c = ExtractGaitCycle(layout_, SyntheticWalk(400, 130));
  ASSERT_TRUE(c.clean) << c.problem;
  const Eigen::VectorXd back = c.poses.col(PoseChannel("lowerback.ry"));
  for (int k = 1; k < back.size(); ++k) EXPECT_LT(std::abs(back[k] - back[k - 1]), 5.0) << k;
  EXPECT_GT(back.maxCoeff(), 180.0);  // continuous through 180, not wrapped to -180
  EXPECT_NEAR(back.mean(), 175, 1.0);
}

TEST_F(GaitCycleTest, FlagsWhatIsNotAWalk) {
  // Still: the thighs do not swing.
  Motion still;
  still.values = RowMatrixXd::Zero(400, skeleton_.NumChannels());
  GaitCycle c = ExtractGaitCycle(layout_, still);
  EXPECT_FALSE(c.clean);
  EXPECT_NE(c.problem.find("barely swing"), std::string::npos) << c.problem;
  // Random flailing: not periodic.
  Motion random = SyntheticWalk(400, 130);
  std::mt19937 generator(5);
  std::normal_distribution<double> step(0, 3);
  double left = 0, right = 0;
  for (int t = 0; t < 400; ++t) {
    left += step(generator);
    right += step(generator);
    random.values(t, Channel("lfemur.rx")) = left;
    random.values(t, Channel("rfemur.rx")) = right;
  }
  c = ExtractGaitCycle(layout_, random);
  EXPECT_FALSE(c.clean);
  // Too short for a stride.
  c = ExtractGaitCycle(layout_, SyntheticWalk(90, 130));
  EXPECT_FALSE(c.clean);
  EXPECT_NE(c.problem.find("too short"), std::string::npos) << c.problem;
  // A walk whose pose drifts over the cycle does not close.
  Motion drifting = SyntheticWalk(400, 130);
  for (int t = 0; t < 400; ++t) drifting.values(t, Channel("lhumerus.rz")) = t * 0.5;
  c = ExtractGaitCycle(layout_, drifting);
  EXPECT_FALSE(c.clean);
  EXPECT_NE(c.problem.find("does not close"), std::string::npos) << c.problem;
}

TEST_F(GaitCycleTest, OptionsCheck) {
  std::string why;
  GaitCycleOptions o;
  EXPECT_TRUE(o.Check(&why));
  o.max_cycle_s = 0.5;
  EXPECT_FALSE(o.Check(&why));
  EXPECT_NE(why.find("min_cycle_s"), std::string::npos);
  EXPECT_FALSE(o.Check(nullptr));  // `why` may be null
}

// GaitPoseLayout takes a skeleton whose femurs turn only about y and z; finding the stride
// needs their flexion (rx): an InputError naming the skeleton, not an abort.
TEST(GaitCycle, ThighsWithoutFlexionAreRefusedNamingTheSkeleton) {
  std::string asf = ReadTextFile(test::CmuRoot() / "subjects/07/07.asf", "asf");
  const std::string femur = "name lfemur";
  const size_t at = asf.find(femur);
  ASSERT_NE(at, std::string::npos);
  const size_t dof = asf.find("dof rx ry rz", at);
  const size_t limits = asf.find("limits (-160.0 20.0)", at);
  const size_t second = asf.find("(-70.0 70.0)", limits);
  ASSERT_NE(dof, std::string::npos);
  ASSERT_NE(second, std::string::npos);
  asf.replace(limits, second + std::string("(-70.0 70.0)").size() - limits, "limits (-70.0 70.0)");  // drop rx's
  asf.replace(dof, std::string("dof rx ry rz").size(), "dof ry rz");
  const Skeleton skeleton = ParseAsf(asf, "no_flexion.asf");
  const GaitPoseLayout layout(skeleton, "no_flexion.asf");
  Motion walk;
  walk.values = RowMatrixXd::Zero(400, skeleton.NumChannels());
  test::ExpectInputError([&] { ExtractGaitCycle(layout, walk); }, {"no_flexion.asf", "lfemur.rx"});
}

// Every walking trial: a clean cycle of a normal length; non-walking trials are flagged.
TEST(CmuGaitCycles, WalkingTrialsHaveCleanCyclesOthersAreFlagged) {
  int clean = 0, walking = 0;
  for (const TrialId& id : test::SplitTrials("walking")) {
    const Skeleton s = ReadAsf(TrialAsfPath(test::CmuRoot(), id));
    const GaitCycle c = ExtractGaitCycle(GaitPoseLayout(s, "asf"), ReadAmc(TrialAmcPath(test::CmuRoot(), id), s));
    ++walking;
    if (!c.clean) {
      std::cout << id.name << " flagged: " << c.problem << "\n";
      continue;
    }
    ++clean;
    EXPECT_GE(c.LengthFrames(), 110) << id.name;  // 0.9-1.6 s at 120 fps
    EXPECT_LE(c.LengthFrames(), 195) << id.name;
    EXPECT_NEAR(c.LengthFrames(), c.period_frames, 0.2 * c.period_frames) << id.name;
  }
  EXPECT_EQ(walking, 42);
  EXPECT_GE(clean, 40);
  for (const char* other : {"118/118_01", "118/118_03", "10/10_01", "05/05_02", "131/131_05", "135/135_04"}) {
    const std::string path = other;
    const std::string subject = path.substr(0, path.find('/'));
    const Skeleton s = ReadAsf(test::CmuRoot() / "subjects" / subject / (subject + ".asf"));
    const GaitCycle c = ExtractGaitCycle(GaitPoseLayout(s, "asf"),
                                         ReadAmc(test::CmuRoot() / "subjects" / (path + ".amc"), s));
    EXPECT_FALSE(c.clean) << other;
  }
}

}  // namespace
}  // namespace jgpm
