#include "io/gait/gait_pose.h"

#include <gtest/gtest.h>

#include "io/mocap/amc.h"
#include "io/mocap/asf.h"
#include "io/mocap/kinematics.h"
#include "test_support.h"

namespace jgpm {
namespace {

class GaitPoseTest : public testing::Test {
 protected:
  GaitPoseTest()
      : skeleton_(ReadAsf(test::CmuRoot() / "subjects/35/35.asf")),
        motion_(ReadAmc(test::CmuRoot() / "subjects/35/35_01.amc", skeleton_)),
        layout_(skeleton_, "35.asf") {}

  // A copy of `frame` turned by `angle_deg` about the vertical axis through the origin.
  std::vector<double> Turned(const double* frame, double angle_deg) const {
    std::vector<double> turned(frame, frame + skeleton_.NumChannels());
    const Eigen::Matrix3d turn = AxisRotation(Axis::kY, angle_deg);
    const Eigen::Matrix3d rotation = turn * layout_.RootRotation(frame);
    std::vector<double> angles;
    RotationToAngles(rotation, RotationAxes(skeleton_.bones[0]), &angles);  // root C = I
    const Eigen::Vector3d position = turn * Eigen::Vector3d(frame[0], frame[1], frame[2]);
    for (int i = 0; i < 3; ++i) turned[i] = position[i];
    for (int i = 0; i < 3; ++i) turned[3 + i] = angles[i];
    return turned;
  }

  Skeleton skeleton_;
  Motion motion_;
  GaitPoseLayout layout_;
};

TEST_F(GaitPoseTest, EighteenJointsFortyThreeChannels) {
  EXPECT_EQ(GaitJoints().size(), 18u);
  EXPECT_EQ(layout_.NumChannels(), 43);
  EXPECT_EQ(layout_.channel_names()[0], "root.rx");
  EXPECT_EQ(layout_.channel_names()[3], "lowerback.rx");
  ASSERT_EQ(layout_.measured_columns().size(), 17u);
  // "neck" ends at the upper neck; the femur joint at the knee (femur end).
  EXPECT_EQ(layout_.measured_columns()[3], skeleton_.FindBone("upperneck"));
  EXPECT_EQ(layout_.measured_columns()[5], skeleton_.FindBone("lfemur"));
  EXPECT_EQ(layout_.channel_joints()[layout_.NumChannels() - 1], 17);
}

TEST_F(GaitPoseTest, ToFrameKeepsTheGaitChannelsAndZeroesTheRest) {
  std::vector<double> pose(43), frame(skeleton_.NumChannels());
  layout_.FromFrame(motion_.Frame(10), 0.0, pose.data());
  layout_.ToFrame(pose.data(), frame.data());
  const auto& kept = layout_.skeleton_channels();
  for (int c = 0; c < skeleton_.NumChannels(); ++c) {
    const bool is_kept = std::find(kept.begin(), kept.end(), c) != kept.end();
    if (!is_kept) {
      EXPECT_EQ(frame[c], 0.0) << skeleton_.ChannelNames()[c];
    } else if (c >= 6) {
      EXPECT_NEAR(WrapDegrees(frame[c] - motion_.values(10, c)), 0.0, 1e-9);
    }
  }
  // The root rotation is reproduced too (heading 0 removes nothing).
  EXPECT_TRUE(layout_.RootRotation(frame.data()).isApprox(layout_.RootRotation(motion_.Frame(10)), 1e-12));
}

TEST_F(GaitPoseTest, RemovingTheHeadingMakesTurnedWalksEqual) {
  for (double turn : {-170.0, -45.0, 30.0, 120.0}) {
    const std::vector<double> turned = Turned(motion_.Frame(50), turn);
    const double heading = HeadingOf(layout_.RootRotation(motion_.Frame(50)));
    std::vector<double> a(43), b(43);
    layout_.FromFrame(motion_.Frame(50), heading, a.data());
    layout_.FromFrame(turned.data(), heading + turn, b.data());
    for (int c = 0; c < 43; ++c) EXPECT_NEAR(WrapDegrees(a[c] - b[c]), 0, 1e-9) << c;
    // And the result faces +z.
    std::vector<double> frame(skeleton_.NumChannels());
    layout_.ToFrame(b.data(), frame.data());
    EXPECT_NEAR(HeadingOf(layout_.RootRotation(frame.data())), 0, 1e-9);
  }
}

// The placed ToFrame undoes FromFrame: a real frame's pose and heading, with its root
// translation, give back every joint where the motion had it.
TEST_F(GaitPoseTest, PlacedToFrameInvertsFromFrame) {
  const Kinematics kinematics(skeleton_);
  for (int f : {0, 77, 150}) {
    const double* original = motion_.Frame(f);
    const double heading = HeadingOf(layout_.RootRotation(original));
    std::vector<double> pose(43), frame(skeleton_.NumChannels());
    layout_.FromFrame(original, heading, pose.data());
    layout_.ToFrame(pose.data(), heading, Eigen::Vector3d(original[0], original[1], original[2]), frame.data());
    // Only the gait channels survive, so compare with the original reduced to them.
    std::vector<double> reduced(skeleton_.NumChannels(), 0.0);
    for (int c : layout_.skeleton_channels()) reduced[c] = original[c];
    for (int c = 0; c < 3; ++c) reduced[c] = original[c];
    const Eigen::Matrix3Xd expected = kinematics.Compute(reduced.data()), got = kinematics.Compute(frame.data());
    EXPECT_LT((expected - got).cwiseAbs().maxCoeff(), 1e-6) << "frame " << f;
    EXPECT_NEAR(HeadingOf(layout_.RootRotation(frame.data())), heading, 1e-9);
  }
}

TEST_F(GaitPoseTest, KinematicsGivesTheMeasuredJointsOfToFrame) {
  const GaitPoseKinematics fk(skeleton_, "35.asf");
  std::vector<double> pose(43), frame(skeleton_.NumChannels());
  layout_.FromFrame(motion_.Frame(20), 0.0, pose.data());
  Eigen::Matrix3Xd joints;
  fk.Compute(pose.data(), &joints);
  ASSERT_EQ(joints.cols(), 17);
  layout_.ToFrame(pose.data(), frame.data());
  const Eigen::Matrix3Xd all = Kinematics(skeleton_).Compute(frame.data());
  for (int j = 0; j < 17; ++j) EXPECT_EQ(joints.col(j), all.col(layout_.measured_columns()[j]));
  // The root sits at the origin, so the head is about a torso's length above it.
  EXPECT_GT(joints.col(4).y(), 400);
}

TEST(GaitPose, HeadingOfByHand) {
  EXPECT_NEAR(HeadingOf(Eigen::Matrix3d::Identity()), 0, 1e-12);
  EXPECT_NEAR(HeadingOf(AxisRotation(Axis::kY, 90)), 90, 1e-12);   // facing +x
  EXPECT_NEAR(HeadingOf(AxisRotation(Axis::kY, -120)), -120, 1e-12);
  // Tilting forward does not change the heading.
  EXPECT_NEAR(HeadingOf(AxisRotation(Axis::kY, 40) * AxisRotation(Axis::kX, 20)), 40, 1e-9);
}

TEST(GaitPose, SkeletonWithoutTheGaitBones) {
  const Skeleton small = ParseAsf(test::SmallAsfText(), "small.asf");
  test::ExpectInputError([&] { GaitPoseLayout(small, "small.asf"); },
                         {"small.asf", "no bone 'lowerback'", "'lowerback'"});
}

}  // namespace
}  // namespace jgpm
