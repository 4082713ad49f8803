// The camera guessed for an uncalibrated video, against hand-computed projections: the
// view's centre, its edge at half the field of view, the tilt, the camera's height.
#include "calibration/camera_guess.h"

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

namespace jgpm {
namespace {

TEST(GuessCamera, SeesWhatItsFieldOfViewTiltAndHeightSay) {
  CameraGuess guess;
  guess.fov_deg = 60;
  guess.height_mm = 1200;
  guess.tilt_deg = 10;
  const Camera camera = GuessCamera("cam0", 320, 240, guess);
  std::string why;
  ASSERT_TRUE(camera.Check(&why)) << why;
  EXPECT_TRUE(camera.CentreInWorld().isApprox(Eigen::Vector3d(0, 1200, 0), 1e-9));
  // Straight along the view (10 degrees down from +z): the image centre.
  const double t = 10 * std::numbers::pi / 180;
  Eigen::Vector2d pixel;
  ASSERT_TRUE(camera.Project(Eigen::Vector3d(0, 1200 - 3000 * std::sin(t), 3000 * std::cos(t)), &pixel));
  EXPECT_NEAR(pixel.x(), 159.5, 1e-6);
  EXPECT_NEAR(pixel.y(), 119.5, 1e-6);
  // Half the field of view to the side, in the camera's horizontal plane: the image's edge.
  const Eigen::Matrix3d r = camera.cam_from_world_rotation;
  const Eigen::Vector3d side = camera.CentreInWorld() + r.transpose() * Eigen::Vector3d(std::tan(30 * std::numbers::pi / 180), 0, 1) * 2000;
  ASSERT_TRUE(camera.Project(side, &pixel));
  EXPECT_NEAR(pixel.x(), 159.5 + 160, 1e-6);
  // The floor straight ahead is below the centre (the camera looks down at it), and world
  // up is image up.
  ASSERT_TRUE(camera.Project(Eigen::Vector3d(0, 0, 4000), &pixel));
  EXPECT_GT(pixel.y(), 119.5);
  Eigen::Vector2d higher;
  ASSERT_TRUE(camera.Project(Eigen::Vector3d(0, 1000, 4000), &higher));
  EXPECT_LT(higher.y(), pixel.y());
}

}  // namespace
}  // namespace jgpm
