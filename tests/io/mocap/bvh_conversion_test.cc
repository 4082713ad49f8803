#include "io/mocap/bvh_conversion.h"

#include <gtest/gtest.h>

#include "io/mocap/amc.h"
#include "io/mocap/asf.h"
#include "io/mocap/kinematics.h"
#include "test_support.h"

namespace jgpm {
namespace {

using test::ExpectInputError;

// Largest distance (mm) between the BVH's joints and the ASF joints they stand for.
double BvhVersusAcclaim(const Bvh& bvh, const Skeleton& skeleton,
                        const std::vector<Eigen::Matrix3Xd>& acclaim) {
  const std::vector<int> column = BvhJointToAcclaimColumn(bvh, skeleton);
  double worst = 0;
  Eigen::Matrix3Xd joints;
  for (int f = 0; f < bvh.frames.rows(); ++f) {
    ComputeBvhPose(bvh, f, &joints);
    for (size_t j = 0; j < column.size(); ++j) {
      EXPECT_GE(column[j], 0);
      worst = std::max(worst, (joints.col(j) - acclaim[f].col(column[j])).norm());
    }
  }
  return worst;
}

TEST(BvhConversion, StructureOfTheSmallSkeleton) {
  const Skeleton s = ParseAsf(test::SmallAsfText(), "small.asf");
  Motion m;
  m.values = RowMatrixXd::Zero(1, s.NumChannels());
  const Bvh bvh = AcclaimToBvh(s, m);
  std::vector<std::string> names;
  for (const BvhJoint& j : bvh.joints) names.push_back(j.end_site ? "End" : j.name);
  // Leaves (shin, spine) end in End Sites.
  EXPECT_EQ(names, (std::vector<std::string>{"root", "hip", "thigh", "shin", "End", "spine", "End"}));
  EXPECT_EQ(bvh.joints[0].channels.size(), 6u);
  EXPECT_EQ(bvh.joints[1].channels.size(), 3u);  // a dof-less bone still gets channels
  EXPECT_DOUBLE_EQ(bvh.frame_time, 1.0 / 120.0);
  // The thigh joint sits at the hip bone's end: 2 units along x, in centimetres.
  EXPECT_TRUE(bvh.joints[2].offset.isApprox(Eigen::Vector3d(2 * 2.54 / 0.45, 0, 0)));
}

// Every CMU trial: AMC -> BVH text -> BVH joint positions, and back -> AMC -> positions,
// agree with the AMC's own forward kinematics to 1e-6 mm.
TEST(BvhConversion, RoundTripKeepsJointPositionsOnEveryCmuTrial) {
  std::map<std::filesystem::path, Skeleton> skeletons;
  double worst_bvh = 0, worst_back = 0;
  int trials = 0;
  for (const test::CmuTrial& trial : test::AllCmuTrials()) {
    SCOPED_TRACE(trial.amc.string());
    auto it = skeletons.find(trial.asf);
    if (it == skeletons.end()) it = skeletons.emplace(trial.asf, ReadAsf(trial.asf)).first;
    const Skeleton& s = it->second;
    const Motion m = ReadAmc(trial.amc, s);
    const std::vector<Eigen::Matrix3Xd> original = ComputeJointPositions(s, m);

    const Bvh bvh = ParseBvh(FormatBvh(AcclaimToBvh(s, m)), "exported.bvh");
    const double bvh_error = BvhVersusAcclaim(bvh, s, original);
    const Motion back = BvhToAcclaim(bvh, s, "exported.bvh");
    const Motion reread = ParseAmc(FormatAmc(back, s), "back.amc", s);
    const std::vector<Eigen::Matrix3Xd> again = ComputeJointPositions(s, reread);
    double back_error = 0;
    for (size_t f = 0; f < again.size(); ++f) {
      back_error = std::max(back_error, (again[f] - original[f]).colwise().norm().maxCoeff());
    }
    EXPECT_LT(bvh_error, 1e-6);
    EXPECT_LT(back_error, 1e-6);
    worst_bvh = std::max(worst_bvh, bvh_error);
    worst_back = std::max(worst_back, back_error);
    ++trials;
  }
  std::cout << trials << " trials: AMC->BVH worst joint error " << worst_bvh
            << " mm; AMC->BVH->AMC worst " << worst_back << " mm\n";
  EXPECT_GE(trials, 70);
}

class BvhToAcclaimErrors : public testing::Test {
 protected:
  BvhToAcclaimErrors() : skeleton_(ParseAsf(test::SmallAsfText(), "small.asf")) {
    Motion m;
    m.values = RowMatrixXd::Zero(2, skeleton_.NumChannels());
    m.values(1, 6) = 30;  // thigh rx
    bvh_ = AcclaimToBvh(skeleton_, m);
  }
  Skeleton skeleton_;
  Bvh bvh_;
};

TEST_F(BvhToAcclaimErrors, RecoversTheMotion) {
  const Motion m = BvhToAcclaim(bvh_, skeleton_, "ok.bvh");
  EXPECT_NEAR(m.values(1, 6), 30, 1e-9);
  EXPECT_NEAR(m.values(1, 7), 0, 1e-9);
}

TEST_F(BvhToAcclaimErrors, MissingJoint) {
  bvh_.joints[3].name = "knee";  // was shin
  ExpectInputError([&] { BvhToAcclaim(bvh_, skeleton_, "x.bvh"); }, {"x.bvh", "no joint 'shin'"});
}

TEST_F(BvhToAcclaimErrors, OtherSkeleton) {
  bvh_.joints[3].offset *= 1.5;  // shin placed further down the thigh
  ExpectInputError([&] { BvhToAcclaim(bvh_, skeleton_, "x.bvh"); }, {"x.bvh", "'shin' OFFSET does not match"});
}

TEST_F(BvhToAcclaimErrors, WrongUnit) {
  bvh_.mm_per_unit = 1.0;
  ExpectInputError([&] { BvhToAcclaim(bvh_, skeleton_, "x.bvh"); }, {"BVH unit"});
}

TEST_F(BvhToAcclaimErrors, RotationAboutAnAxisTheBoneCannotTurn) {
  // The shin has only rx; turn it about z in frame 2.
  const int shin = bvh_.FindJoint("shin");
  bvh_.frames(1, bvh_.ChannelOffsets()[shin]) = 12;  // its Zrotation channel
  ExpectInputError([&] { BvhToAcclaim(bvh_, skeleton_, "x.bvh"); },
                   {"x.bvh", "frame 2", "'shin'", "no dof for"});
}

TEST_F(BvhToAcclaimErrors, WrongHierarchy) {
  std::swap(bvh_.joints[3].name, bvh_.joints[5].name);  // shin under the root, spine under the thigh
  ExpectInputError([&] { BvhToAcclaim(bvh_, skeleton_, "x.bvh"); }, {"x.bvh", "'shin' must be a child of 'thigh'"});
}

}  // namespace
}  // namespace jgpm
