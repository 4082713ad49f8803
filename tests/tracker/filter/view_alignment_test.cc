// Each camera's residual misalignment, learnt from what it sees (tracker/filter/view_alignment.h):
// the best shift is the one that was applied; a camera whose view is displaced gets that
// displacement as its offset; a person who moved along the floor, seen consistently by
// every camera, is the person's move and leaves the offsets at zero; one camera alone
// learns nothing; no offset passes its limit.
#include "tracker/filter/view_alignment.h"

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

namespace jgpm {
namespace {

// A person-like blob (an upright ellipse, 1.7 m by 0.5 m) where `camera` sees `at_mm`
// (the floor point), displaced by `shift` pixels.
cv::Mat Blob(const Camera& camera, const Eigen::Vector3d& at_mm, const cv::Point2d& shift = {0, 0}) {
  cv::Mat image = cv::Mat::zeros(camera.height, camera.width, CV_8UC1);
  Eigen::Vector2d top, bottom;
  EXPECT_TRUE(camera.Project(at_mm + Eigen::Vector3d(0, 1700, 0), &top));
  EXPECT_TRUE(camera.Project(at_mm, &bottom));
  const cv::Point2d centre = cv::Point2d(0.5 * (top.x() + bottom.x()), 0.5 * (top.y() + bottom.y())) + shift;
  const double height = bottom.y() - top.y();
  cv::ellipse(image, cv::Point(static_cast<int>(std::lround(centre.x)), static_cast<int>(std::lround(centre.y))),
              cv::Size(static_cast<int>(std::lround(height * 0.15)), static_cast<int>(std::lround(height / 2))), 0, 0,
              360, 255, cv::FILLED);
  return image;
}

std::vector<Camera> TwoCameras() {
  return {LookAtCamera("side", 320, 240, 300, {4000, 1500, 0}, {0, 1000, 0}),
          LookAtCamera("front", 320, 240, 300, {300, 1500, 4000}, {0, 1000, 0})};
}

TEST(ViewAlignment, TheBestShiftIsTheOneApplied) {
  const Camera camera = TwoCameras()[0];
  const cv::Mat silhouette = Blob(camera, Eigen::Vector3d::Zero());
  for (const cv::Point shift : {cv::Point(2, -1), cv::Point(-3, 3), cv::Point(0, 0)}) {
    const cv::Mat mask = Blob(camera, Eigen::Vector3d::Zero(), shift);
    EXPECT_EQ(ViewAlignment::BestShift(silhouette, mask, cv::Rect(0, 0, 320, 240), 3), shift);
  }
}

// The tracker's loop: the estimate stays where the person is; camera 0 sees the world
// displaced by (0, 5) px (a tilt error); its offset learns it, the other camera's stays.
TEST(ViewAlignment, ADisplacedViewLearnsItsDisplacement) {
  const std::vector<Camera> cameras = TwoCameras();
  ViewAlignment alignment(cameras, {});
  ASSERT_TRUE(alignment.active());
  const Eigen::Vector3d person(100, 0, -200);
  const cv::Point2d error(0, 5);
  const std::vector<cv::Mat> seen = {Blob(cameras[0], person, error), Blob(cameras[1], person)};
  const std::vector<cv::Mat> silhouettes = {Blob(cameras[0], person), Blob(cameras[1], person)};
  const std::vector<cv::Rect> regions(2, cv::Rect(0, 0, 320, 240));
  for (int frame = 0; frame < 80; ++frame) {
    alignment.Update(silhouettes, {alignment.Apply(0, seen[0]), alignment.Apply(1, seen[1])}, regions, person);
  }
  std::printf("offsets: (%.2f, %.2f) and (%.2f, %.2f)\n", alignment.offset(0).x, alignment.offset(0).y,
              alignment.offset(1).x, alignment.offset(1).y);
  // A vertical displacement of the side view is hardly a move along the floor; what is
  // left after taking that out is the error, within a pixel.
  EXPECT_NEAR(alignment.offset(0).y, 5, 1.0);
  EXPECT_NEAR(alignment.offset(0).x, 0, 1.0);
  EXPECT_LT(std::hypot(alignment.offset(1).x, alignment.offset(1).y), 1.0);
  EXPECT_EQ(cv::countNonZero(alignment.Apply(0, seen[0]) != silhouettes[0]), 0);  // lined up again
}

// The person 150 mm from where the estimate is, seen so by both cameras: a move along the
// floor explains every shift, so the cameras keep no offset (the tracker moves the person).
TEST(ViewAlignment, AConsistentMoveIsThePersonsNotTheCameras) {
  const std::vector<Camera> cameras = TwoCameras();
  ViewAlignment alignment(cameras, {});
  const Eigen::Vector3d estimate(0, 0, 0), person(60, 0, 60);
  const std::vector<cv::Mat> seen = {Blob(cameras[0], person), Blob(cameras[1], person)};
  const std::vector<cv::Mat> silhouettes = {Blob(cameras[0], estimate), Blob(cameras[1], estimate)};
  ASSERT_NE(ViewAlignment::BestShift(silhouettes[0], seen[0], cv::Rect(0, 0, 320, 240), 3), cv::Point(0, 0));
  for (int frame = 0; frame < 40; ++frame) {
    alignment.Update(silhouettes, {alignment.Apply(0, seen[0]), alignment.Apply(1, seen[1])},
                     std::vector<cv::Rect>(2, cv::Rect(0, 0, 320, 240)), estimate);
  }
  for (int c = 0; c < 2; ++c) EXPECT_LT(std::hypot(alignment.offset(c).x, alignment.offset(c).y), 0.6) << c;
}

TEST(ViewAlignment, OneCameraLearnsNothingAndOffsetsStayWithinTheirLimits) {
  const std::vector<Camera> cameras = TwoCameras();
  ViewAlignment lone({cameras[0]}, {});
  EXPECT_FALSE(lone.active());
  const Eigen::Vector3d person(0, 0, 0);
  lone.Update({Blob(cameras[0], person)}, {Blob(cameras[0], person, {3, 3})}, {cv::Rect(0, 0, 320, 240)}, person);
  EXPECT_EQ(lone.offset(0), cv::Point2d(0, 0));
  // A view displaced far beyond any calibration's error: the offset stops at the limit,
  // 2 (f tan 0.7 deg + 4 px) = 2 (300 x 0.0122 + 4) = 15.3 px.
  ViewAlignment alignment(cameras, {});
  EXPECT_NEAR(alignment.limit_px(0), 2 * (300 * std::tan(0.7 * std::numbers::pi / 180) + 4), 1e-9);
  const std::vector<cv::Mat> silhouettes = {Blob(cameras[0], person), Blob(cameras[1], person)};
  for (int frame = 0; frame < 300; ++frame) {
    const std::vector<cv::Mat> seen = {Blob(cameras[0], person, {0, 40}), Blob(cameras[1], person)};
    alignment.Update(silhouettes, {alignment.Apply(0, seen[0]), alignment.Apply(1, seen[1])},
                     std::vector<cv::Rect>(2, cv::Rect(0, 0, 320, 240)), person);
  }
  EXPECT_LE(std::hypot(alignment.offset(0).x, alignment.offset(0).y), alignment.limit_px(0) + 1e-9);
  EXPECT_GT(std::hypot(alignment.offset(0).x, alignment.offset(0).y), 0.9 * alignment.limit_px(0));
}

}  // namespace
}  // namespace jgpm
