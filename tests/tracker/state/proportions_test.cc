// Limb proportions against hand-computed kinematics: each limb bone's length changes by
// its proportion and nothing else moves; the placed body still stands on the floor.
#include "tracker/state/proportions.h"

#include <gtest/gtest.h>

#include "io/gait/gait_pose.h"
#include "io/mocap/amc.h"
#include "io/mocap/asf.h"
#include "io/mocap/kinematics.h"
#include "test_support.h"
#include "tracker/state/state_model.h"

namespace jgpm {
namespace {

TEST(ProportionsTest, LimbBonesScaleAboutTheirLimbsBase) {
  const Skeleton skeleton = ReadAsf(test::CmuRoot() / "subjects/35/35.asf");
  const Motion motion = ReadAmc(test::CmuRoot() / "subjects/35/35_01.amc", skeleton);
  Eigen::Matrix3Xd before = Kinematics(skeleton).Compute(motion.Frame(50));
  before.colwise() -= Eigen::Vector3d(before.col(0));
  Eigen::Matrix3Xd after = before;
  double foot = -1;
  const LimbScaler limbs(skeleton);
  limbs.Apply({}, &after, &foot);
  EXPECT_EQ(after, before);
  EXPECT_EQ(foot, -1);  // untouched at proportions 1
  limbs.Apply({0.9, 1.1}, &after, &foot);
  const auto b = [&](const char* name) { return skeleton.FindBone(name); };
  const auto length = [&](const Eigen::Matrix3Xd& j, const char* from, const char* to) {
    return (j.col(b(to)) - j.col(b(from))).norm();
  };
  for (const char* s : {"l", "r"}) {
    const std::string side = s;
    const auto n = [&](const char* bone) { return side + bone; };
    EXPECT_NEAR(length(after, n("hipjoint").c_str(), n("femur").c_str()),
                0.9 * length(before, n("hipjoint").c_str(), n("femur").c_str()), 1e-9);
    EXPECT_NEAR(length(after, n("femur").c_str(), n("tibia").c_str()),
                0.9 * length(before, n("femur").c_str(), n("tibia").c_str()), 1e-9);
    EXPECT_NEAR(length(after, n("clavicle").c_str(), n("humerus").c_str()),
                1.1 * length(before, n("clavicle").c_str(), n("humerus").c_str()), 1e-9);
    EXPECT_NEAR(length(after, n("radius").c_str(), n("wrist").c_str()),
                1.1 * length(before, n("radius").c_str(), n("wrist").c_str()), 1e-9);
    // The limbs' bases and the trunk stay.
    EXPECT_EQ(after.col(b(n("hipjoint").c_str())), before.col(b(n("hipjoint").c_str())));
    EXPECT_EQ(after.col(b(n("clavicle").c_str())), before.col(b(n("clavicle").c_str())));
  }
  EXPECT_EQ(after.col(b("head")), before.col(b("head")));
  EXPECT_EQ(after.col(b("thorax")), before.col(b("thorax")));
  double lowest = 1e300;
  for (int f : skeleton.FootBones()) lowest = std::min(lowest, after(1, f));
  EXPECT_EQ(foot, lowest);

  // Placed, shorter legs still stand on the floor: the body comes down, the head with it.
  PosePlacer placer(skeleton);
  const GaitPoseLayout layout(skeleton, "35.asf");
  Eigen::VectorXd pose(layout.NumChannels());
  layout.FromFrame(motion.Frame(50), 0, pose.data());
  Eigen::Matrix3Xd normal, short_legs;
  placer.Place(pose.data(), 0, 0, 0, 1, &normal);
  placer.SetProportions({0.9, 1});
  placer.Place(pose.data(), 0, 0, 0, 1, &short_legs);
  double low_normal = 1e300, low_short = 1e300;
  for (int f : skeleton.FootBones()) low_normal = std::min(low_normal, normal(1, f)), low_short = std::min(low_short, short_legs(1, f));
  EXPECT_NEAR(low_short, kFootClearanceMm, 1e-9);
  EXPECT_NEAR(low_normal, kFootClearanceMm, 1e-9);
  const double hip_height = normal(1, b("lhipjoint")) - low_normal;
  EXPECT_NEAR(normal(1, b("head")) - short_legs(1, b("head")), 0.1 * hip_height, 0.15 * hip_height);
  EXPECT_GT(normal(1, b("head")) - short_legs(1, b("head")), 40);
}

TEST(ProportionsTest, ASkeletonWithoutLimbsIsNamed) {
  Skeleton skeleton = ReadAsf(test::CmuRoot() / "subjects/35/35.asf");
  skeleton.bones[skeleton.FindBone("rhumerus")].name = "rupperarm";
  test::ExpectInputError([&] { LimbScaler limbs(skeleton); }, {"'rhumerus'"});
}

}  // namespace
}  // namespace jgpm
