// SLERP in-betweening (prior/motion/slerp_transition.h) against hand-computed cases: a one-dof knee
// moves linearly in its angle (also across +/-180 degrees, the short way), the root's
// translation linearly, every three-dof bone along the geodesic at constant angular speed;
// the ends are the two poses themselves (joint positions by forward kinematics).
#include "prior/motion/slerp_transition.h"

#include <cmath>
#include <random>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "io/mocap/asf.h"
#include "io/mocap/kinematics.h"
#include "io/mocap/rotation.h"
#include "test_support.h"

namespace jgpm {
namespace {

using test::ExpectInputError;

struct Fixture {
  Skeleton skeleton = ParseAsf(test::GaitAsfText(), "gait.asf");
  int Channel(const std::string& name) const {
    const std::vector<std::string> names = skeleton.ChannelNames();
    return static_cast<int>(std::find(names.begin(), names.end(), name) - names.begin());
  }
  Eigen::RowVectorXd RandomPose(std::mt19937* rng) const {
    std::uniform_real_distribution<double> u(-120, 120);
    Eigen::RowVectorXd pose(skeleton.NumChannels());
    for (auto& v : pose) v = u(*rng);
    return pose;
  }
};

// Dof rotation of one bone in a pose (as the header defines it).
Eigen::Matrix3d BoneRotation(const Skeleton& s, int bone, const Eigen::RowVectorXd& pose) {
  const int first = s.ChannelOffsets()[bone];
  Eigen::Matrix3d m = Eigen::Matrix3d::Identity();
  for (size_t k = 0; k < s.bones[bone].dofs.size(); ++k) {
    if (IsRotation(s.bones[bone].dofs[k])) m = AxisRotation(DofAxis(s.bones[bone].dofs[k]), pose(first + k)) * m;
  }
  return m;
}

double Angle(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) {
  return Eigen::AngleAxisd(a.transpose() * b).angle();
}

TEST(SlerpTransition, EndsAreTheTwoPoses) {
  const Fixture f;
  std::mt19937 rng(3);
  const Kinematics kinematics(f.skeleton);
  for (int trial = 0; trial < 10; ++trial) {
    const Eigen::RowVectorXd a = f.RandomPose(&rng), b = f.RandomPose(&rng);
    EXPECT_LT((SlerpPose(f.skeleton, a, b, 0, a) - a).cwiseAbs().maxCoeff(), 1e-9);
    EXPECT_LT((SlerpPose(f.skeleton, a, b, 1, b) - b).cwiseAbs().maxCoeff(), 1e-9);
    // Whatever frame the angles continue from, t = 1 is b's pose (its joints, to 1e-6 mm).
    const Eigen::RowVectorXd end = SlerpPose(f.skeleton, a, b, 1, a);
    EXPECT_LT((kinematics.Compute(end.data()) - kinematics.Compute(b.data())).cwiseAbs().maxCoeff(), 1e-6);
  }
}

TEST(SlerpTransition, ThreeDofBonesFollowTheGeodesicAtConstantSpeed) {
  const Fixture f;
  std::mt19937 rng(4);
  const Eigen::RowVectorXd a = f.RandomPose(&rng), b = f.RandomPose(&rng);
  const int frames = 7;
  const RowMatrixXd path = SlerpTransition(f.skeleton, a, b, frames);
  for (size_t bone = 0; bone < f.skeleton.bones.size(); ++bone) {
    if (RotationAxes(f.skeleton.bones[bone]).size() != 3) continue;
    const Eigen::Matrix3d ma = BoneRotation(f.skeleton, bone, a), mb = BoneRotation(f.skeleton, bone, b);
    const double total = Angle(ma, mb);
    for (int i = 1; i <= frames; ++i) {
      const Eigen::Matrix3d m = BoneRotation(f.skeleton, bone, path.row(i - 1));
      const double t = static_cast<double>(i) / (frames + 1);
      EXPECT_NEAR(Angle(ma, m), t * total, 1e-9) << f.skeleton.bones[bone].name << " frame " << i;
      EXPECT_NEAR(Angle(m, mb), (1 - t) * total, 1e-9) << f.skeleton.bones[bone].name << " frame " << i;
    }
  }
}

TEST(SlerpTransition, OneDofAndTranslationMoveLinearlyTheShortWay) {
  const Fixture f;
  Eigen::RowVectorXd a = Eigen::RowVectorXd::Zero(f.skeleton.NumChannels()), b = a;
  const int knee = f.Channel("ltibia.rx"), other = f.Channel("rtibia.rx"), tx = f.Channel("root.tx");
  a(knee) = 10, b(knee) = 70;
  a(other) = 170, b(other) = -170;  // 20 degrees apart across 180
  a(tx) = -5, b(tx) = 7;
  const RowMatrixXd path = SlerpTransition(f.skeleton, a, b, 5);
  for (int i = 1; i <= 5; ++i) {
    EXPECT_NEAR(path(i - 1, knee), 10 + 10 * i, 1e-9);
    EXPECT_NEAR(path(i - 1, other), 170 + 20.0 * i / 6, 1e-9);
    EXPECT_NEAR(path(i - 1, tx), -5 + 2 * i, 1e-12);
  }
}

TEST(SlerpTransition, RefusesBadInput) {
  const Fixture f;
  const Eigen::RowVectorXd a = Eigen::RowVectorXd::Zero(f.skeleton.NumChannels());
  ExpectInputError([&] { SlerpTransition(f.skeleton, a, a, 0); }, {"frames"});
  ExpectInputError([&] { SlerpTransition(f.skeleton, a, Eigen::RowVectorXd::Zero(3), 5); }, {"channels"});
  Eigen::RowVectorXd bad = a;
  bad(4) = NAN;
  ExpectInputError([&] { SlerpTransition(f.skeleton, a, bad, 5); }, {"non-finite"});
}

}  // namespace
}  // namespace jgpm
