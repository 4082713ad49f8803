#include "io/mocap/kinematics.h"

#include <gtest/gtest.h>

#include "io/mocap/amc.h"
#include "io/mocap/asf.h"
#include "test_support.h"

namespace jgpm {
namespace {

// Hand-computed poses of the small test skeleton (test_support.h). One unit is
// 25.4 / 0.45 mm. At rest: hip ends at (2,0,0), thigh at (2,-4,0), shin at (2,-7,0), spine
// at (0,5,0) units.
class SmallSkeletonKinematics : public testing::Test {
 protected:
  SmallSkeletonKinematics() : skeleton_(ParseAsf(test::SmallAsfText(), "small.asf")), fk_(skeleton_) {}

  // Frame vector: root(tx ty tz rx ry rz) thigh(rx rz) shin(rx) spine(rx ry rz).
  Eigen::Matrix3Xd Pose(std::vector<double> frame) const {
    frame.resize(12, 0.0);
    return fk_.Compute(frame.data());
  }
  Eigen::Vector3d Units(double x, double y, double z) const {
    return Eigen::Vector3d(x, y, z) * (25.4 / 0.45);
  }
  int Column(const char* bone) const { return skeleton_.FindBone(bone); }

  Skeleton skeleton_;
  Kinematics fk_;
};

TEST_F(SmallSkeletonKinematics, RestPose) {
  const Eigen::Matrix3Xd j = Pose({});
  EXPECT_TRUE(j.col(0).isZero());
  EXPECT_TRUE(j.col(Column("hip")).isApprox(Units(2, 0, 0)));
  EXPECT_TRUE(j.col(Column("thigh")).isApprox(Units(2, -4, 0)));
  EXPECT_TRUE(j.col(Column("shin")).isApprox(Units(2, -7, 0)));
  EXPECT_TRUE(j.col(Column("spine")).isApprox(Units(0, 5, 0)));
}

TEST_F(SmallSkeletonKinematics, DofRotatesAboutTheBonesLocalAxis) {
  // thigh axis C = Rz(90): its local z is world z, so rz = 90 swings (0,-1,0) to (1,0,0);
  // the shin follows.
  Eigen::Matrix3Xd j = Pose({0, 0, 0, 0, 0, 0, /*thigh rx rz*/ 0, 90});
  EXPECT_LT((j.col(Column("thigh")) - Units(6, 0, 0)).norm(), 1e-9);
  EXPECT_LT((j.col(Column("shin")) - Units(9, 0, 0)).norm(), 1e-9);
  // Its local x is world y: rx = 90 turns about world y, leaving the thigh (along -y) in
  // place; the shin's own rx = 90 takes (0,-1,0) to (0,0,-1), then the thigh's turn to (-1,0,0).
  j = Pose({0, 0, 0, 0, 0, 0, 90, 0, /*shin rx*/ 90});
  EXPECT_LT((j.col(Column("thigh")) - Units(2, -4, 0)).norm(), 1e-9);
  EXPECT_LT((j.col(Column("shin")) - Units(-1, -4, 0)).norm(), 1e-9);
}

TEST_F(SmallSkeletonKinematics, DofsApplyInTheirListedOrder) {
  // "dof rx rz": M = Rz Rx. With rx = rz = 90 the thigh points along +x: (6,0,0). The
  // other order (Rx Rz) would give (2,0,-4).
  const Eigen::Matrix3Xd j = Pose({0, 0, 0, 0, 0, 0, 90, 90});
  EXPECT_LT((j.col(Column("thigh")) - Units(6, 0, 0)).norm(), 1e-9);
}

TEST_F(SmallSkeletonKinematics, RootTranslationIsInLengthUnitsAndRotationTurnsEverything) {
  // Root at (1,2,3) units, turned 90 degrees about y: hip (1,0,0) -> (0,0,-1).
  const Eigen::Matrix3Xd j = Pose({1, 2, 3, 0, 90, 0});
  EXPECT_LT((j.col(0) - Units(1, 2, 3)).norm(), 1e-9);
  EXPECT_LT((j.col(Column("hip")) - Units(1, 2, 1)).norm(), 1e-9);
  EXPECT_LT((j.col(Column("thigh")) - Units(1, -2, 1)).norm(), 1e-9);
  EXPECT_LT((j.col(Column("spine")) - Units(1, 7, 3)).norm(), 1e-9);
  // 1 unit = 56.444 mm for `length 0.45`.
  EXPECT_NEAR(j.col(0).x(), 56.4444444, 1e-6);
}

TEST_F(SmallSkeletonKinematics, RotationsAreReturnedWhenAsked) {
  std::vector<double> frame(12, 0.0);
  frame[4] = 90;  // root ry
  Eigen::Matrix3Xd joints;
  std::vector<Eigen::Matrix3d> rotations;
  fk_.Compute(frame.data(), &joints, &rotations);
  ASSERT_EQ(rotations.size(), 5u);
  EXPECT_TRUE(rotations[Column("shin")].isApprox(AxisRotation(Axis::kY, 90)));
}

// Real CMU trials: every bone keeps its ASF length in every frame (relative 1e-6), and the
// root starts where the AMC puts it.
TEST(CmuKinematics, BoneLengthsStayConstantOnEveryTrial) {
  std::map<std::filesystem::path, Skeleton> skeletons;
  double worst = 0;
  long frames = 0;
  for (const test::CmuTrial& trial : test::AllCmuTrials()) {
    auto it = skeletons.find(trial.asf);
    if (it == skeletons.end()) it = skeletons.emplace(trial.asf, ReadAsf(trial.asf)).first;
    const Skeleton& s = it->second;
    const Motion m = ReadAmc(trial.amc, s);
    const std::vector<Eigen::Matrix3Xd> joints = ComputeJointPositions(s, m);
    for (const Eigen::Matrix3Xd& j : joints) {
      for (size_t b = 1; b < s.bones.size(); ++b) {
        const double expected = s.bones[b].length * s.MillimetresPerUnit();
        const double actual = (j.col(b) - j.col(s.bones[b].parent)).norm();
        worst = std::max(worst, std::abs(actual - expected) / expected);
      }
      ASSERT_TRUE(j.allFinite()) << trial.amc;
    }
    const Eigen::Vector3d root = m.values.row(0).head<3>().transpose() * s.MillimetresPerUnit();
    EXPECT_LT((joints[0].col(0) - root).norm(), 1e-9) << trial.amc;
    frames += m.NumFrames();
  }
  std::cout << "checked " << frames << " frames; worst relative bone-length error " << worst << "\n";
  EXPECT_LT(worst, 1e-6);
  EXPECT_GT(frames, 50000);
}

TEST(CmuKinematics, WalkerIsUprightAndHumanSized) {
  const Skeleton s = ReadAsf(test::CmuRoot() / "subjects/35/35.asf");
  const Motion m = ReadAmc(test::CmuRoot() / "subjects/35/35_01.amc", s);
  const Eigen::Matrix3Xd j = Kinematics(s).Compute(m.Frame(0));
  const double head = j.col(s.FindBone("head")).y();
  const double toe = std::min(j.col(s.FindBone("ltoes")).y(), j.col(s.FindBone("rtoes")).y());
  EXPECT_GT(head - toe, 1400);  // an adult, in millimetres
  EXPECT_LT(head - toe, 2000);
}

}  // namespace
}  // namespace jgpm
