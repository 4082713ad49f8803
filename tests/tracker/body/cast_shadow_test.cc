// The drawn shadow against the ray-cast one (shadow_oracle.h).
#include "tracker/body/cast_shadow.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "tracker/body/shadow_oracle.h"

namespace jgpm {
namespace {

// A standing figure of tapered parts: legs apart, a trunk, a head, an arm out.
std::vector<Capsule> Figure(const Eigen::Vector3d& at) {
  const auto part = [&](Eigen::Vector3d a, Eigen::Vector3d b, double ra, double rb) {
    return Capsule{at + a, at + b, ra, rb};
  };
  return {part({-120, 60, 80}, {-90, 850, 0}, 55, 75),   part({120, 60, -150}, {90, 850, 0}, 55, 75),
          part({0, 900, 0}, {0, 1450, 0}, 150, 130),      part({0, 1620, 0}, {0, 1630, 0}, 100, 100),
          part({200, 1400, 0}, {550, 1100, 100}, 45, 35)};
}

Eigen::Vector3d Light(double elevation_deg, double azimuth_deg) {
  const double e = elevation_deg * std::numbers::pi / 180, a = azimuth_deg * std::numbers::pi / 180;
  return {std::cos(e) * std::sin(a), std::sin(e), std::cos(e) * std::cos(a)};
}

cv::Mat RayCastShadow(const Camera& camera, const std::vector<Capsule>& parts, const Eigen::Vector3d& light,
                      double floor_mm) {
  cv::Mat shadow(camera.height, camera.width, CV_8U, cv::Scalar(0));
  test::AddRayCastShadow(camera, parts, light, floor_mm, &shadow);
  return shadow;
}

// The shadow drawn into a packed mask over the whole image, as a CV_8U image.
cv::Mat Drawn(const Camera& camera, const std::vector<Capsule>& parts, const Eigen::Vector3d& light, double floor_mm) {
  BitMask mask(camera.width, camera.height);
  DrawCastShadow(CapsuleProjector(camera), parts, light, floor_mm, cv::Rect(0, 0, camera.width, camera.height), &mask);
  return mask.ToMat();
}

// Pixels where the two differ that are more than a pixel from the oracle's edge (the
// polygons' chords and the fill's rounding stay within it), and the overlap's IoU.
void Compare(const cv::Mat& drawn, const cv::Mat& truth, int* far_off, double* iou) {
  cv::Mat grown, shrunk;
  cv::dilate(truth, grown, cv::Mat());
  cv::erode(truth, shrunk, cv::Mat());
  *far_off = cv::countNonZero(drawn & ~grown) + cv::countNonZero(shrunk & ~drawn);
  const int both = cv::countNonZero(drawn & truth), either = cv::countNonZero(drawn | truth);
  *iou = either > 0 ? double(both) / either : 1;
}

TEST(DrawCastShadow, MatchesARayCastShadowThroughLevelHighAndDistortedCameras) {
  const Eigen::Vector3d at(300, 0, 4000);
  const std::vector<Capsule> parts = Figure(at);
  Camera level = LookAtCamera("level", 320, 240, 300, {0, 1500, 0}, {300, 600, 4000});
  Camera high = LookAtCamera("high", 320, 240, 420, {-3000, 6000, -2000}, at);
  Camera wide = LookAtCamera("wide", 320, 240, 170, {900, 1200, 1500}, {300, 300, 4000});
  wide.distortion = {-0.12, 0.02, 0, 0, 0};
  int checked = 0;
  for (const Camera& camera : {level, high, wide}) {
    for (const auto& [elevation, azimuth] : {std::pair{25.0, 0.0}, {40.0, 100.0}, {55.0, 200.0}, {70.0, 290.0}}) {
      const Eigen::Vector3d light = Light(elevation, azimuth);
      for (const double floor : {0.0, 60.0}) {
        const cv::Mat drawn = Drawn(camera, parts, light, floor);
        const cv::Mat truth = RayCastShadow(camera, parts, light, floor);
        int far_off;
        double iou;
        Compare(drawn, truth, &far_off, &iou);
        SCOPED_TRACE(camera.name + " elevation " + std::to_string(elevation) + " floor " + std::to_string(floor));
        const int area = cv::countNonZero(truth);
        ASSERT_GT(area, 250);
        // A pixel is in when its centre is, in both, but the polygons' chords and the
        // oracle's floor points differ along the outline: a pixel's ring at most, a sixth of
        // a 300-pixel shadow.
        EXPECT_GT(iou, 0.75);
        // Beyond that ring: the polygons' chords, and the lens bending their edges.
        EXPECT_LE(far_off, std::max(3, area / 100));
        ++checked;
      }
    }
  }
  EXPECT_EQ(checked, 24);
}

TEST(DrawCastShadow, ALightAtOrBelowTheHorizonCastsNothingOnTheFloor) {
  const Camera camera = LookAtCamera("level", 160, 120, 150, {0, 1500, 0}, {0, 600, 4000});
  EXPECT_EQ(cv::countNonZero(Drawn(camera, Figure({0, 0, 4000}), Light(0, 30), 0)), 0);
  EXPECT_EQ(cv::countNonZero(Drawn(camera, Figure({0, 0, 4000}), Light(-20, 30), 0)), 0);
}

TEST(DrawCastShadow, AShadowBehindTheCameraIsLeftOut) {
  // The figure stands just in front of a camera looking away from the light's far side:
  // most of its shadow falls behind the camera, which sees only the part in front.
  const Camera camera = LookAtCamera("near", 160, 120, 150, {0, 1500, 0}, {0, 0, 3000});
  const std::vector<Capsule> parts = Figure({0, 0, 1800});
  const Eigen::Vector3d light = Light(30, 0);  // from +z: the shadow falls towards -z
  const cv::Mat drawn = Drawn(camera, parts, light, 0);
  const cv::Mat truth = RayCastShadow(camera, parts, light, 0);
  // What is drawn is shadow the camera sees (a part whose shadow reaches behind the
  // camera is left out whole, not drawn wrapped round the image).
  cv::Mat grown;
  cv::dilate(truth, grown, cv::Mat());
  EXPECT_GT(cv::countNonZero(truth), 0);
  EXPECT_LE(cv::countNonZero(drawn & ~grown), 3);
}

}  // namespace
}  // namespace jgpm
