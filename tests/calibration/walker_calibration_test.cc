// Calibration from walkers against the cameras that saw them: head and foot points
// projected through a known camera (a surveillance camera high above a plaza, a webcam at a
// desk, a lens with distortion), walkers of drawn heights on walks at several distances,
// pixel noise; the camera must come back within its stated uncertainty, and a walk that
// cannot determine it must be refused.
#include "calibration/walker_calibration.h"

#include <cmath>
#include <numbers>
#include <random>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "io/base/error.h"
#include "tests/calibration/true_camera.h"

namespace jgpm {
namespace {

constexpr double kDeg = std::numbers::pi / 180;

// A camera at `height_mm` above the origin looking along +z, `tilt_deg` down, rolled.
Camera Placed(int width, int height, double focal, double height_mm, double tilt_deg, double roll_deg) {
  const Eigen::Vector3d centre(0, height_mm, 0);
  const double t = tilt_deg * kDeg;
  Camera camera = LookAtCamera("truth", width, height, focal, centre,
                               centre + Eigen::Vector3d(0, -std::sin(t), std::cos(t)));
  camera.cam_from_world_rotation =
      Eigen::AngleAxisd(roll_deg * kDeg, Eigen::Vector3d::UnitZ()).toRotationMatrix() * camera.cam_from_world_rotation;
  camera.cam_from_world_translation_mm = -camera.cam_from_world_rotation * centre;
  return camera;
}

struct Walk {
  Eigen::Vector3d from, to;  // floor points, mm
};

// The top of a round head's image whose top point is `top`: the highest of points all
// over its upper half (radius 90 mm), found by brute force.
bool SilhouetteTop(const Camera& camera, const Eigen::Vector3d& top, Eigen::Vector2d* pixel) {
  const double r = 90;
  const Eigen::Vector3d centre = top - Eigen::Vector3d(0, r, 0);
  bool any = false;
  for (int i = 0; i <= 45; ++i) {  // the upper half, in 2-degree steps
    for (int j = 0; j < 180; ++j) {
      const double polar = i * std::numbers::pi / 90, azimuth = j * std::numbers::pi / 90;
      const Eigen::Vector3d p = centre + r * Eigen::Vector3d(std::sin(polar) * std::cos(azimuth), std::cos(polar),
                                                             std::sin(polar) * std::sin(azimuth));
      Eigen::Vector2d q;
      if (camera.Project(p, &q) && (!any || q.y() < pixel->y())) {
        *pixel = q;
        any = true;
      }
    }
  }
  return any;
}

// Every walker on its walk, `frames` points each, heights drawn around 1700 +- 90 mm: a
// round head's silhouette top and the foot point 15% of the height up, the head leaning
// forward along the walk by 2-6 degrees, the points given noise of `noise_px`; points
// outside the image are dropped, as a blob touching the edge would be.
std::vector<HeadFoot> Observe(const Camera& camera, const std::vector<Walk>& walks, int frames, double noise_px,
                              unsigned seed, double* mean_height = nullptr) {
  std::mt19937 random(seed);
  std::normal_distribution<double> stature(1700, 90), noise(0, noise_px);
  std::uniform_real_distribution<double> lean_deg(2, 6);
  std::vector<HeadFoot> points;
  double sum = 0;
  for (size_t w = 0; w < walks.size(); ++w) {
    const double height = stature(random);
    sum += height;
    const Eigen::Vector3d lean =
        (walks[w].to - walks[w].from).normalized() * height * std::tan(lean_deg(random) * kDeg);
    for (int i = 0; i < frames; ++i) {
      const Eigen::Vector3d foot = walks[w].from + (walks[w].to - walks[w].from) * i / (frames - 1.0);
      HeadFoot point;
      point.walker = static_cast<int>(w) * 7 + 3;  // any numbering
      // The foot point: the centroid of the legs' lowest 30%, 15% of the height up
      // (WalkerCalibrationOptions::foot_share).
      if (!camera.Project(foot + Eigen::Vector3d(0, 0.15 * height, 0), &point.foot_px) ||
          !SilhouetteTop(camera, foot + lean + Eigen::Vector3d(0, height, 0), &point.head_px))
        continue;
      auto inside = [&](const Eigen::Vector2d& p) {
        return p.x() > 0 && p.y() > 0 && p.x() < camera.width - 1 && p.y() < camera.height - 1;
      };
      if (!inside(point.foot_px) || !inside(point.head_px)) continue;
      point.head_px += Eigen::Vector2d(noise(random), noise(random));
      point.foot_px += Eigen::Vector2d(noise(random), noise(random));
      points.push_back(point);
    }
  }
  if (mean_height) *mean_height = sum / walks.size();
  return points;
}

// Walks across and along the view at 6-20 m from a camera over a plaza: 6, and 6 more.
std::vector<Walk> PlazaWalks() {
  return {{{-6000, 0, 8000}, {6000, 0, 9000}},   {{5000, 0, 12000}, {-5000, 0, 11000}},
          {{-4000, 0, 16000}, {4000, 0, 18000}}, {{-2000, 0, 7000}, {1000, 0, 19000}},
          {{3000, 0, 20000}, {2000, 0, 8000}},   {{-7000, 0, 14000}, {7000, 0, 14500}},
          {{6000, 0, 7000}, {-6000, 0, 7500}},   {{-5000, 0, 10000}, {5000, 0, 10500}},
          {{4000, 0, 18000}, {-4000, 0, 15000}}, {{2500, 0, 6500}, {-1500, 0, 17000}},
          {{-3000, 0, 19000}, {-2000, 0, 9000}}, {{7000, 0, 13000}, {-7000, 0, 12000}}};
}

void ExpectRecovered(const WalkerCalibration& found, const Camera& truth, double mean_height_mm) {
  const CameraAngles angles = AnglesOf(truth);
  // The scale comes from the prior's 1700 mm: the camera's height is the truth's times
  // 1700 over the walkers' mean height, give or take what the heights' spread allows.
  const double height_expected = angles.height_mm * 1700 / mean_height_mm;
  EXPECT_NEAR(found.focal_px.value, truth.fx, std::max(3 * found.focal_px.sd, 1e-6)) << "focal";
  EXPECT_NEAR(found.focal_px.value, truth.fx, 0.05 * truth.fx) << "focal";
  EXPECT_NEAR(found.height_mm.value, height_expected, 3 * found.height_mm.sd) << "height";
  EXPECT_NEAR(found.height_mm.value, angles.height_mm, 0.06 * angles.height_mm) << "height";
  EXPECT_NEAR(found.tilt_deg.value, angles.tilt_deg, std::max(3 * found.tilt_deg.sd, 0.3)) << "tilt";
  EXPECT_NEAR(found.roll_deg.value, angles.roll_deg, std::max(3 * found.roll_deg.sd, 0.3)) << "roll";
  // The camera written is the one reported.
  const CameraAngles written = AnglesOf(found.camera);
  EXPECT_NEAR(written.tilt_deg, found.tilt_deg.value, 1e-9);
  EXPECT_NEAR(written.roll_deg, found.roll_deg.value, 1e-9);
  EXPECT_NEAR(written.height_mm, found.height_mm.value, 1e-6);
  std::string why;
  EXPECT_TRUE(found.camera.Check(&why)) << why;
}

TEST(CalibrateFromWalkers, RecoversAnElevatedCameraOverAPlaza) {
  const Camera truth = Placed(640, 480, 700, 6000, 28, 2.5);
  double mean_height;
  const auto points = Observe(truth, PlazaWalks(), 60, 0.7, 1, &mean_height);
  ASSERT_GT(points.size(), 200u);
  const WalkerCalibration found = CalibrateFromWalkers(points, 640, 480);
  EXPECT_EQ(found.walkers, 12);
  ExpectRecovered(found, truth, mean_height);
  // The stated uncertainty is small: a few percent, a degree.
  EXPECT_LT(found.focal_px.sd / found.focal_px.value, 0.07);
  EXPECT_LT(found.height_mm.sd / found.height_mm.value, 0.06);
  EXPECT_LT(found.tilt_deg.sd, 1.5);
  // Each walker's height, up to the common scale.
  EXPECT_EQ(found.walker_heights_mm.size(), 12u);
}

TEST(CalibrateFromWalkers, AWebcamAtADeskNeedsItsFieldOfView) {
  // A wide webcam 1.3 m up, nearly level, walkers 2.5-7 m away. Level, the head-foot
  // ratios do not depend on the focal length (the vertical vanishing point is at
  // infinity): walkers cannot tell it, and it must be refused; given it (a webcam's stated
  // field of view), the rest is found.
  const Camera truth = Placed(640, 480, 330, 1300, 8, -1.5);
  const std::vector<Walk> walks = {{{-2500, 0, 5000}, {2500, 0, 5500}}, {{2000, 0, 3500}, {-2000, 0, 3000}},
                                   {{-1000, 0, 7000}, {500, 0, 3000}},  {{1500, 0, 2800}, {1000, 0, 7500}},
                                   {{-3000, 0, 6500}, {3000, 0, 6000}}, {{1500, 0, 4500}, {-2500, 0, 4000}},
                                   {{-500, 0, 3000}, {-1500, 0, 7000}}, {{2500, 0, 7000}, {1000, 0, 2800}}};
  double mean_height;
  const auto points = Observe(truth, walks, 60, 0.7, 2, &mean_height);
  try {
    CalibrateFromWalkers(points, 640, 480);
    ADD_FAILURE() << "a nearly level camera's focal length was not refused";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("focal length"), std::string::npos) << e.what();
  }
  WalkerCalibrationOptions options;
  options.intrinsics = LookAtCamera("fov", 640, 480, 330, Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitZ());
  ExpectRecovered(CalibrateFromWalkers(points, 640, 480, options), truth, mean_height);
}

TEST(CalibrateFromWalkers, KeepsTheUsersLensAndFitsThePose) {
  Camera truth = test::TrueCamera();  // distorted, principal point off-centre
  const Camera pose = Placed(640, 480, truth.fx, 4000, 20, 1);
  truth.cam_from_world_rotation = pose.cam_from_world_rotation;
  truth.cam_from_world_translation_mm = pose.cam_from_world_translation_mm;
  double mean_height;
  const auto points = Observe(truth, PlazaWalks(), 40, 0.5, 3, &mean_height);
  WalkerCalibrationOptions options;
  options.intrinsics = test::TrueCamera();
  const WalkerCalibration found = CalibrateFromWalkers(points, 640, 480, options);
  EXPECT_EQ(found.focal_px.value, truth.fx);
  EXPECT_EQ(found.focal_px.sd, 0);
  EXPECT_EQ(found.camera.distortion, truth.distortion);
  EXPECT_EQ(found.camera.cx, truth.cx);
  ExpectRecovered(found, truth, mean_height);
}

TEST(CalibrateFromWalkers, RefusesOneWalkerOnOneLineOfSight) {
  // Straight away from the camera along its axis: every head-foot line is the same image
  // column, which says nothing of the focal length.
  const Camera truth = Placed(640, 480, 700, 6000, 28, 0);
  const auto points = Observe(truth, {{{0, 0, 9000}, {0, 0, 16000}}}, 80, 0.7, 4);
  ASSERT_GE(points.size(), 20u);
  try {
    CalibrateFromWalkers(points, 640, 480);
    FAIL() << "expected a refusal";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("do not determine"), std::string::npos) << e.what();
  }
}

TEST(CalibrateFromWalkers, RefusesTooFewPointsAndPointsThatAreNoFloor) {
  const Camera truth = Placed(640, 480, 700, 6000, 28, 0);
  const auto walks = PlazaWalks();
  auto points = Observe(truth, {walks.begin(), walks.begin() + 3}, 5, 0.7, 5);  // 15 points
  EXPECT_THROW(CalibrateFromWalkers(points, 640, 480), InputError);
  // Upside down: heads below feet.
  points = Observe(truth, PlazaWalks(), 20, 0.7, 5);
  for (HeadFoot& point : points) std::swap(point.head_px, point.foot_px);
  try {
    const auto found = CalibrateFromWalkers(points, 640, 480);
    ADD_FAILURE() << "heads below feet gave f " << found.focal_px.value << " h " << found.height_mm.value << " tilt "
                  << found.tilt_deg.value << " roll " << found.roll_deg.value << " rms " << found.rms_height_mm;
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("the right way up"), std::string::npos) << e.what();
  }
  points[3].head_px.x() = std::nan("");
  EXPECT_THROW(CalibrateFromWalkers(points, 640, 480), InputError);
}

TEST(CalibrateFromWalkers, UncertaintyFallsWithMoreWalkers) {
  const Camera truth = Placed(640, 480, 700, 6000, 28, 2.5);
  const auto walks = PlazaWalks();
  const auto few = CalibrateFromWalkers(Observe(truth, {walks.begin(), walks.begin() + 6}, 60, 0.7, 6), 640, 480);
  const auto many = CalibrateFromWalkers(Observe(truth, walks, 60, 0.7, 6), 640, 480);
  EXPECT_LT(many.height_mm.sd, few.height_mm.sd);
  EXPECT_LT(many.focal_px.sd, few.focal_px.sd);
}

}  // namespace
}  // namespace jgpm
