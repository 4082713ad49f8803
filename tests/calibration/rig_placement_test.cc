// Several cameras placed from the walkers they share, against the cameras that saw them:
// three surveillance cameras around a plaza (one of them rolled), a crowd of twelve walkers
// two or three at a time, each camera calibrated on its own from its view of them and then
// placed; the rig must match the truth's placement up to the stature prior's scale, and a
// camera that sees other people, or whose clock disagrees, must be refused, unless its
// clock's offset is searched for, which must then find it.
#include "calibration/rig_placement.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "io/base/error.h"
#include "tests/calibration/observed_walkers.h"

namespace jgpm {
namespace {

using test::kDeg;

constexpr int kFrames = 60, kStagger = 25;  // each walker's frames; a new one every 25

// cam0 over the plaza's near edge looking along +z; the others across it from the sides.
std::vector<Camera> Truth() {
  Camera cam1 = LookAtCamera("cam1", 640, 480, 650, {15000, 7000, 13000}, {0, 0, 13000});
  Camera cam2 = LookAtCamera("cam2", 800, 600, 900, {-13000, 7000, 25000}, {0, 0, 12000});
  // cam2 rolled by 3 degrees.
  cam2.cam_from_world_rotation =
      Eigen::AngleAxisd(3 * kDeg, Eigen::Vector3d::UnitZ()).toRotationMatrix() * cam2.cam_from_world_rotation;
  cam2.cam_from_world_translation_mm = -cam2.cam_from_world_rotation * Eigen::Vector3d(-13000, 7000, 25000);
  return {test::Placed(640, 480, 700, 6000, 28, 2.5), cam1, cam2};
}

// Each camera calibrated on its own from what it saw.
std::vector<RigCamera> Calibrated(const std::vector<Camera>& truth, const std::vector<test::Walk>& walks,
                                  double* mean_height = nullptr) {
  std::vector<RigCamera> rig;
  for (const Camera& camera : truth) {
    RigCamera c;
    c.points = test::Observe(camera, walks, kFrames, 0.7, 7, mean_height, kStagger);
    c.calibration = CalibrateFromWalkers(c.points, camera.width, camera.height);
    rig.push_back(c);
  }
  return rig;
}

TEST(PlaceRig, PlacesThreeCamerasAroundAPlazaFromTheCrowdTheyShare) {
  const std::vector<Camera> truth = Truth();
  double mean_height;
  const std::vector<RigCamera> cameras = Calibrated(truth, test::PlazaWalks(), &mean_height);
  const RigPlacement rig = PlaceRig(cameras);
  ASSERT_EQ(rig.cameras.size(), 3u);
  // The figures, for the log: each camera's own calibration, refined, and the truth.
  for (int k = 0; k < 3; ++k) {
    const WalkerCalibration& own = cameras[k].calibration;
    const PlacedCamera& r = rig.cameras[k];
    std::printf("cam%d: focal %.0f -> %.0f (truth %.0f) px, tilt %.2f -> %.2f (%.2f) deg, yaw %.2f +- %.2f (%.2f) "
                "deg, floor point (%.0f, %.0f) +- %.0f mm (truth x %.4f: (%.0f, %.0f)), %d matches, rms %.0f mm\n",
                k, own.focal_px.value, r.focal_px.value, truth[k].fx, own.tilt_deg.value, r.tilt_deg.value,
                AnglesOf(truth[k]).tilt_deg, r.yaw_deg.value, r.yaw_deg.sd, YawOf(truth[k]), r.x_mm.value, r.z_mm.value,
                r.x_mm.sd, 1700 / mean_height, truth[k].CentreInWorld().x() * 1700 / mean_height,
                truth[k].CentreInWorld().z() * 1700 / mean_height, r.matches, r.rms_mm);
  }
  // cam0 stays where its own calibration put it (up to the world's rescaling).
  EXPECT_NEAR(YawOf(rig.cameras[0].camera), 0, 1e-9);
  EXPECT_EQ(rig.cameras[0].placed_against, -1);
  EXPECT_NEAR(rig.cameras[0].camera.CentreInWorld().y(), rig.cameras[0].height_mm.value, 1e-6);
  // The truth's world is cam0's (its floor point the origin, looking along +z), seen at the
  // scale the stature prior implies, give or take the rig's scale error: compare positions
  // relative to cam0's height.
  const double scale = rig.cameras[0].camera.CentreInWorld().y() / truth[0].CentreInWorld().y();
  EXPECT_NEAR(scale, 1700 / mean_height, 0.05);
  for (int k = 1; k < 3; ++k) {
    const PlacedCamera& found = rig.cameras[k];
    SCOPED_TRACE("cam" + std::to_string(k));
    const Eigen::Vector3d centre = found.camera.CentreInWorld(), expected = scale * truth[k].CentreInWorld();
    const double distance = Eigen::Vector2d(expected.x(), expected.z()).norm();
    EXPECT_GT(found.matches, 100);
    EXPECT_LT(found.rms_mm, 200);
    EXPECT_NEAR(found.yaw_deg.value, YawOf(truth[k]), 1.0);
    EXPECT_NEAR(found.yaw_deg.value, YawOf(truth[k]), std::max(3 * found.yaw_deg.sd, 0.2));
    EXPECT_NEAR(centre.x(), expected.x(), 0.02 * distance);
    EXPECT_NEAR(centre.z(), expected.z(), 0.02 * distance);
    EXPECT_NEAR(centre.y(), expected.y(), 0.04 * expected.y());
    EXPECT_NEAR(found.x_mm.value, centre.x(), 1e-6);
    EXPECT_NEAR(found.z_mm.value, centre.z(), 1e-6);
    EXPECT_GT(found.x_mm.sd, 0);
    // The refined angles are the written camera's, and nearer the truth than the camera's
    // own calibration's (the other cameras' view of the same people corrects them).
    const CameraAngles angles = AnglesOf(found.camera), true_angles = AnglesOf(truth[k]);
    EXPECT_NEAR(angles.tilt_deg, found.tilt_deg.value, 1e-6);
    EXPECT_NEAR(angles.roll_deg, found.roll_deg.value, 1e-6);
    EXPECT_NEAR(found.focal_px.value, found.camera.fx, 1e-6);
    EXPECT_NEAR(found.tilt_deg.value, true_angles.tilt_deg, 0.5);
    EXPECT_NEAR(found.tilt_deg.value, true_angles.tilt_deg, std::max(3 * found.tilt_deg.sd, 0.1));
    EXPECT_NEAR(found.focal_px.value, truth[k].fx, 0.025 * truth[k].fx);
    // Floor points across the plaza land where the truth's do, within a few pixels.
    for (double x = -6000; x <= 6000; x += 3000) {
      for (double z = 8000; z <= 20000; z += 4000) {
        Eigen::Vector2d seen, expected_px;
        if (!truth[k].Project({x, 0, z}, &expected_px)) continue;
        ASSERT_TRUE(found.camera.Project(scale * Eigen::Vector3d(x, 0, z), &seen));
        EXPECT_LT((seen - expected_px).norm(), 0.02 * truth[k].width) << x << ", " << z;
      }
    }
    std::string why;
    EXPECT_TRUE(found.camera.Check(&why)) << why;
  }
}

TEST(PlaceRig, RefusesACameraThatSeesOtherPeople) {
  std::vector<Camera> truth = Truth();
  std::vector<RigCamera> cameras = Calibrated(truth, test::PlazaWalks());
  // cam2 sees other people cross the plaza at the same times: the walks mirrored and
  // reversed, and in another order.
  std::vector<test::Walk> others = test::PlazaWalks();
  for (test::Walk& walk : others) {
    std::swap(walk.from, walk.to);
    walk.from.x() *= -1;
    walk.to.x() *= -1;
  }
  std::reverse(others.begin(), others.end());
  cameras[2].points = test::Observe(truth[2], others, kFrames, 0.7, 8, nullptr, kStagger);
  cameras[2].calibration = CalibrateFromWalkers(cameras[2].points, 800, 600);
  try {
    const RigPlacement rig = PlaceRig(cameras);
    ADD_FAILURE() << "placed cam2 at yaw " << rig.cameras[2].yaw_deg.value << " with " << rig.cameras[2].matches
                  << " matches";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("cam2 shares too few walkers"), std::string::npos) << e.what();
    std::printf("%s\n", e.what());
  }
}

TEST(PlaceRig, RefusesClocksThatDisagree) {
  std::vector<RigCamera> cameras = Calibrated(Truth(), test::PlazaWalks());
  cameras.resize(2);
  // cam1's video started 12 frames (0.4 s) late: each walker is 2 m along their walk from
  // where cam0 saw them at that frame number.
  for (HeadFoot& point : cameras[1].points) point.frame -= 12;
  try {
    const RigPlacement rig = PlaceRig(cameras);
    ADD_FAILURE() << "placed cam1 at yaw " << rig.cameras[1].yaw_deg.value << " with " << rig.cameras[1].matches
                  << " matches";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("cam1 shares too few walkers"), std::string::npos) << e.what();
    std::printf("%s\n", e.what());
  }
  cameras.resize(1);
  try {
    PlaceRig(cameras);
    ADD_FAILURE() << "one camera placed";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("at least two cameras"), std::string::npos) << e.what();
  }
}

TEST(PlaceRig, FindsHowFarTheClocksDisagree) {
  const std::vector<Camera> truth = Truth();
  std::vector<RigCamera> cameras = Calibrated(truth, test::PlazaWalks());
  const RigPlacement synchronised = PlaceRig(cameras);
  // cam1's video started 12 frames late, cam2's 7 frames early.
  for (HeadFoot& point : cameras[1].points) point.frame -= 12;
  for (HeadFoot& point : cameras[2].points) point.frame += 7;
  RigPlacementOptions options;
  options.max_clock_offset_frames = 45;  // 1.5 s at 30 fps
  const RigPlacement rig = PlaceRig(cameras, options);
  EXPECT_EQ(rig.cameras[0].clock_offset_frames, 0);
  EXPECT_EQ(rig.cameras[1].clock_offset_frames, 12);
  EXPECT_EQ(rig.cameras[2].clock_offset_frames, -7);
  // Placed as with synchronised clocks.
  for (int k = 1; k < 3; ++k) {
    std::printf("cam%d: clock offset %d frames, yaw %.2f (synchronised %.2f, truth %.2f) deg, floor point (%.0f, %.0f) "
                "(synchronised (%.0f, %.0f)) mm\n",
                k, rig.cameras[k].clock_offset_frames, rig.cameras[k].yaw_deg.value,
                synchronised.cameras[k].yaw_deg.value, YawOf(truth[k]), rig.cameras[k].x_mm.value,
                rig.cameras[k].z_mm.value, synchronised.cameras[k].x_mm.value, synchronised.cameras[k].z_mm.value);
    EXPECT_NEAR(rig.cameras[k].yaw_deg.value, synchronised.cameras[k].yaw_deg.value, 0.1);
    EXPECT_NEAR(rig.cameras[k].x_mm.value, synchronised.cameras[k].x_mm.value, 20);
    EXPECT_NEAR(rig.cameras[k].z_mm.value, synchronised.cameras[k].z_mm.value, 20);
    EXPECT_NEAR(rig.cameras[k].tilt_deg.value, synchronised.cameras[k].tilt_deg.value, 0.05);
  }
  // Beyond the search: refused, saying how far it looked.
  options.max_clock_offset_frames = 5;
  try {
    PlaceRig(cameras, options);
    ADD_FAILURE() << "placed with clocks 12 frames apart, searching 5";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("within 5 frames"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace jgpm
