// Calibration from walkers against the cameras that saw them: head and foot points
// projected through a known camera (a surveillance camera high above a plaza, a webcam at a
// desk, a lens with distortion), walkers of drawn heights on walks at several distances,
// pixel noise; the camera must come back within its stated uncertainty, and a walk that
// cannot determine it must be refused.
#include "calibration/walker_calibration.h"

#include <cmath>
#include <numeric>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "io/base/error.h"
#include "tests/calibration/observed_walkers.h"
#include "tests/calibration/true_camera.h"

namespace jgpm {
namespace {

using test::Observe;
using test::Placed;
using test::PlazaWalks;
using test::Walk;

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

// What the spread "with other walkers" claims: how much the camera found would move had
// other people walked by. So: 16 crowds of 12 walkers, each on walks of its own across a
// plaza and unlike the model (each one's foot point at their own share of their height,
// 0.10-0.20, where the fit takes 0.15 for all). Oracle: the spread of the 16 cameras
// found about their mean; the jackknife's, averaged over the crowds, must be within a
// factor of 2 of it (the fit's covariance need not be: it counts each walker's frames
// as evidence, after scaling by their correlation, and misses what the walkers share).
TEST(CalibrateFromWalkers, TheSpreadWithOtherWalkersIsHowFarOtherCrowdsMoveTheCamera) {
  const Camera truth = Placed(640, 480, 700, 6000, 28, 2.5);
  constexpr int kCrowds = 16;
  std::vector<double> focal, height;
  double focal_spread = 0, height_spread = 0, focal_fit = 0, height_fit = 0;
  for (unsigned seed = 1; seed <= kCrowds; ++seed) {
    std::mt19937 random(seed);
    std::uniform_real_distribution<double> x(-7000, 7000), z(6500, 20000);
    std::vector<Walk> walks(12);
    for (Walk& walk : walks) walk = {{x(random), 0, z(random)}, {x(random), 0, z(random)}};
    const auto points = Observe(truth, walks, 60, 0.7, 100 + seed, nullptr, 0, 0.05);
    const WalkerCalibration found = CalibrateFromWalkers(points, 640, 480);
    focal.push_back(found.focal_px.value);
    height.push_back(found.height_mm.value);
    focal_spread += found.focal_px.walkers_sd / kCrowds, height_spread += found.height_mm.walkers_sd / kCrowds;
    focal_fit += found.focal_px.sd / kCrowds, height_fit += found.height_mm.sd / kCrowds;
  }
  auto sd = [](const std::vector<double>& v) {
    double mean = 0, sum2 = 0;
    for (double x : v) mean += x / v.size();
    for (double x : v) sum2 += (x - mean) * (x - mean);
    return std::sqrt(sum2 / (v.size() - 1));
  };
  auto mean = [](const std::vector<double>& v) { return std::accumulate(v.begin(), v.end(), 0.0) / v.size(); };
  std::printf("focal length: the %d crowds' cameras %.1f px on average (truth %.1f), spread %.1f; with other walkers "
              "%.1f, the fit's %.1f\n",
              kCrowds, mean(focal), truth.fx, sd(focal), focal_spread, focal_fit);
  std::printf("height: %.0f mm on average (truth %.0f), spread %.0f; with other walkers %.0f, the fit's %.0f\n",
              mean(height), AnglesOf(truth).height_mm, sd(height), height_spread, height_fit);
  EXPECT_GT(focal_spread, 0.5 * sd(focal));
  EXPECT_LT(focal_spread, 2 * sd(focal));
  EXPECT_GT(height_spread, 0.5 * sd(height));
  EXPECT_LT(height_spread, 2 * sd(height));
}

}  // namespace
}  // namespace jgpm
