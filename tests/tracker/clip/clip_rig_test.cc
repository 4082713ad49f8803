// The rigs of synthetic clips do what they say (heights, angles, distances, how tall the
// walker looks, what leaves the view), and a miscalibrated camera differs from the true one
// by the amounts stated, no more.
#include "tracker/clip/clip_rig.h"

#include <cmath>
#include <numbers>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "io/mocap/amc.h"
#include "io/mocap/asf.h"
#include "io/mocap/kinematics.h"
#include "test_support.h"

namespace jgpm {
namespace {

constexpr double kDeg = std::numbers::pi / 180;

const std::vector<Eigen::Matrix3Xd>& Walk() {
  static const std::vector<Eigen::Matrix3Xd> walk = [] {
    const Skeleton skeleton = ReadAsf(test::CmuRoot() / "subjects/07/07.asf");
    const Motion motion = ReadAmc(test::CmuRoot() / "subjects/07/07_01.amc", skeleton);
    const Kinematics kinematics(skeleton);
    std::vector<Eigen::Matrix3Xd> joints;
    for (int f = 0; f < motion.NumFrames(); f += 4) {
      joints.emplace_back();
      kinematics.Compute(motion.Frame(f), &joints.back());
    }
    return joints;
  }();
  return walk;
}

// The walk's centre at 1 m height.
Eigen::Vector3d Centre() {
  Eigen::Vector2d lo(1e300, 1e300), hi(-1e300, -1e300);
  for (const Eigen::Matrix3Xd& j : Walk()) {
    lo = lo.cwiseMin(Eigen::Vector2d(j(0, 0), j(2, 0)));
    hi = hi.cwiseMax(Eigen::Vector2d(j(0, 0), j(2, 0)));
  }
  return {0.5 * (lo.x() + hi.x()), 1000, 0.5 * (lo.y() + hi.y())};
}

// The walker's image height (pixels) in `camera` at frame k: head above feet.
double ImageHeight(const Camera& camera, const Eigen::Matrix3Xd& joints) {
  double top = 1e300, bottom = -1e300;
  for (int c = 0; c < joints.cols(); ++c) {
    Eigen::Vector2d p;
    if (!camera.Project(joints.col(c), &p)) continue;
    top = std::min(top, p.y());
    bottom = std::max(bottom, p.y());
  }
  return bottom - top;
}

TEST(MakeRig, TheRingIsTheDefaultRig) {
  RigOptions options;
  options.num_cameras = 3;
  const std::vector<Camera> a = MakeRig(Walk(), options, 9), b = DefaultRig(Walk(), options);
  ASSERT_EQ(a.size(), 3u);
  for (int c = 0; c < 3; ++c) {
    EXPECT_EQ(a[c].fx, b[c].fx);
    EXPECT_EQ(a[c].cam_from_world_rotation, b[c].cam_from_world_rotation);
    EXPECT_EQ(a[c].width, 320);
  }
}

TEST(MakeRig, SurveillanceCamerasAreHighFarAndSeeSmallPeople) {
  RigOptions options;
  options.kind = RigKind::kSurveillance;
  options.num_cameras = 4;
  const Eigen::Vector3d centre = Centre();
  for (uint64_t seed = 1; seed <= 6; ++seed) {
    const std::vector<Camera> cameras = MakeRig(Walk(), options, seed);
    ASSERT_EQ(cameras.size(), 4u);
    for (const Camera& c : cameras) {
      EXPECT_EQ(c.width, 640);
      EXPECT_EQ(c.height, 480);
      const Eigen::Vector3d at = c.CentreInWorld();
      EXPECT_GE(at.y(), 4000);
      EXPECT_LE(at.y(), 8000);
      const double distance = std::hypot(at.x() - centre.x(), at.z() - centre.z());
      EXPECT_GE(distance, 8000 - 1e-6);
      EXPECT_LE(distance, 19300);
      // Looking down at the walk's centre, 20-40 degrees (a little less when 8 m away
      // forces it).
      const Eigen::Vector3d axis = c.cam_from_world_rotation.row(2).transpose();
      const double down = std::asin(-axis.y()) / kDeg;
      EXPECT_GE(down, 20.5 - 1e-6);
      EXPECT_LE(down, 40 + 1e-6);
      // People 60-150 px tall at the walk's middle frame (less when the walk must fit).
      const double height = ImageHeight(c, Walk()[Walk().size() / 2]);
      EXPECT_LT(height, 150 * 1.15) << seed;
      EXPECT_GT(height, 35) << seed;
      // The whole walk in view.
      for (const Eigen::Matrix3Xd& j : Walk()) {
        Eigen::Vector2d p;
        ASSERT_TRUE(c.Project(j.col(0), &p));
        EXPECT_TRUE(p.x() > 0 && p.x() < 640 && p.y() > 0 && p.y() < 480) << seed;
      }
    }
  }
}

TEST(MakeRig, AWebcamIsLowWideNearAndLosesTheWalkerAtTheSides) {
  RigOptions options;
  options.kind = RigKind::kWebcam;
  options.num_cameras = 1;
  int cut_feet = 0, left_view = 0;
  for (uint64_t seed = 1; seed <= 8; ++seed) {
    const std::vector<Camera> cameras = MakeRig(Walk(), options, seed);
    ASSERT_EQ(cameras.size(), 1u);
    const Camera& c = cameras[0];
    const double fov = 2 * std::atan(c.width / (2 * c.fx)) / kDeg;
    EXPECT_GE(fov, 60 - 1e-9);
    EXPECT_LE(fov, 90 + 1e-9);
    EXPECT_GE(c.CentreInWorld().y(), 1000);
    EXPECT_LE(c.CentreInWorld().y(), 1500);
    int in_view = 0;
    bool feet_cut = false;
    for (const Eigen::Matrix3Xd& j : Walk()) {
      Eigen::Vector2d root;
      const bool seen = c.Project(j.col(0), &root) && root.x() > 0 && root.x() < c.width;
      in_view += seen;
      Eigen::Vector2d foot;
      for (int b = 0; b < j.cols(); ++b)
        if (seen && j(1, b) < 150 && c.Project(j.col(b), &foot) && foot.y() > c.height) feet_cut = true;
    }
    EXPECT_GT(in_view, 0.5 * Walk().size()) << seed;  // mostly in view...
    left_view += in_view < static_cast<int>(Walk().size());  // ...but not always
    cut_feet += feet_cut;
  }
  EXPECT_GE(left_view, 6);
  EXPECT_GE(cut_feet, 4);
  // One camera only.
  options.num_cameras = 2;
  std::string why;
  EXPECT_FALSE(options.Check(&why));
  EXPECT_NE(why.find("one camera"), std::string::npos);
}

TEST(Miscalibrate, DiffersByRealisticAmountsTimesTheScale) {
  const Camera truth = LookAtCamera("cam0", 640, 480, 500, {3000, 1500, -2000}, {0, 1000, 0});
  std::mt19937_64 rng(4);
  double largest_focal = 0, largest_turn = 0, largest_move = 0, largest_pp = 0;
  for (double scale : {0.5, 1.0, 2.0}) {
    for (int trial = 0; trial < 200; ++trial) {
      const Camera c = Miscalibrate(truth, scale, &rng);
      std::string why;
      ASSERT_TRUE(c.Check(&why)) << why;
      EXPECT_EQ(c.name, truth.name);
      const double focal = std::abs(c.fx / truth.fx - 1) / scale;
      const double pp = std::max(std::abs(c.cx - truth.cx), std::abs(c.cy - truth.cy)) / scale;
      const double turn =
          Eigen::AngleAxisd(c.cam_from_world_rotation * truth.cam_from_world_rotation.transpose()).angle() / kDeg / scale;
      const double move = (c.CentreInWorld() - truth.CentreInWorld()).norm() / scale;
      EXPECT_LE(focal, 0.015 + 1e-12);
      EXPECT_LE(pp, 4 + 1e-9);
      EXPECT_LE(turn, 0.7 + 1e-9);
      EXPECT_LE(move, 30 + 1e-9);
      EXPECT_EQ(c.fx, c.fy);
      largest_focal = std::max(largest_focal, focal);
      largest_pp = std::max(largest_pp, pp);
      largest_turn = std::max(largest_turn, turn);
      largest_move = std::max(largest_move, move);
    }
  }
  // Not much smaller either: the amounts are reached.
  EXPECT_GT(largest_focal, 0.013);
  EXPECT_GT(largest_pp, 3.5);
  EXPECT_GT(largest_turn, 0.6);
  EXPECT_GT(largest_move, 25);
  const Camera same = Miscalibrate(truth, 0, &rng);
  EXPECT_EQ(same.cam_from_world_rotation, truth.cam_from_world_rotation);
  EXPECT_EQ(same.fx, truth.fx);
}

TEST(RigKind, NamesParseBack) {
  for (RigKind k : {RigKind::kRing, RigKind::kSurveillance, RigKind::kWebcam}) {
    RigKind back = RigKind::kRing;
    EXPECT_TRUE(ParseRigKind(RigKindName(k), &back));
    EXPECT_EQ(back, k);
  }
  RigKind kind = RigKind::kWebcam;
  EXPECT_FALSE(ParseRigKind("blimp", &kind));
  EXPECT_EQ(kind, RigKind::kWebcam);
}

}  // namespace
}  // namespace jgpm
