// A camera's prepared mask (tracker/filter/observation.h) against brute force: inside the region
// the truncated distance to the nearest foreground pixel is the whole image's, computed
// pixel by pixel over every foreground pixel; small enclosed holes are filled (and counted)
// without touching the caller's mask; foreground far from the region (clutter) neither
// counts nor pulls the outline; an empty mask or region gives the truncation everywhere.
#include "tracker/filter/observation.h"

#include <cmath>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

namespace jgpm {
namespace {

constexpr double kTruncation = 10;

// The definition: distance between pixel centres, less 0.75, in [0, truncation].
float BruteDistance(const cv::Mat& mask, int u, int v) {
  double best = 1e9;
  for (int y = 0; y < mask.rows; ++y)
    for (int x = 0; x < mask.cols; ++x)
      if (mask.at<uint8_t>(y, x)) best = std::min(best, std::hypot(x - u, y - v));
  return static_cast<float>(std::clamp(best - 0.75, 0.0, kTruncation));
}

struct Scene {
  cv::Mat mask, filled;  // as given; with the person's hole filled
  cv::Rect region, hole, clutter;
};

Scene MakeScene() {
  Scene s;
  s.mask = cv::Mat::zeros(90, 120, CV_8UC1);
  cv::ellipse(s.mask, cv::Point(45, 45), cv::Size(14, 30), 10, 0, 360, cv::Scalar(255), cv::FILLED);
  cv::line(s.mask, cv::Point(45, 45), cv::Point(70, 60), cv::Scalar(255), 3);  // an arm
  s.hole = cv::Rect(43, 40, 3, 4);
  s.filled = s.mask.clone();
  s.mask(s.hole).setTo(0);
  s.mask(cv::Rect(83, 20, 4, 5)).setTo(255);  // just outside the region: it pulls points inside
  s.clutter = cv::Rect(108, 5, 8, 8);        // far from the person, near the image's edge
  s.mask(s.clutter).setTo(255);
  s.filled(s.clutter).setTo(255);
  s.filled(cv::Rect(83, 20, 4, 5)).setTo(255);
  s.region = cv::Rect(25, 10, 55, 72);
  return s;
}

TEST(CameraObservation, DistancesInTheRegionEqualBruteForce) {
  const Scene s = MakeScene();
  const cv::Mat given = s.mask.clone();
  const CameraObservation o(s.mask, s.region, kTruncation, 60);
  EXPECT_EQ(cv::countNonZero(s.mask != given), 0);  // the caller's mask is untouched
  int checked = 0, inside = 0;
  for (int v = s.region.y; v < s.region.br().y; ++v) {
    for (int u = s.region.x; u < s.region.br().x; ++u) {
      const float expected = BruteDistance(s.filled, u, v);
      ASSERT_NEAR(o.DistanceToForeground(u, v), expected, 1e-4) << u << ", " << v;
      // Sub-pixel points read their pixel.
      ASSERT_EQ(o.DistanceToForeground(u + 0.49f, v - 0.49f), o.DistanceToForeground(u, v));
      ++checked;
      inside += expected > 0 && expected < kTruncation;
    }
  }
  EXPECT_EQ(checked, s.region.area());
  EXPECT_GT(inside, 500);  // the truncation does not hide everything
  EXPECT_LT(o.DistanceToForeground(79, 22), 4.0f);  // near the foreground outside the region
  // The hole is foreground now.
  for (int v = s.hole.y; v < s.hole.br().y; ++v)
    for (int u = s.hole.x; u < s.hole.br().x; ++u) EXPECT_EQ(o.DistanceToForeground(u, v), 0.0f);
  EXPECT_EQ(o.region_count(), cv::countNonZero(s.filled(s.region)));
  EXPECT_EQ(o.Foreground(), cv::countNonZero(s.mask));
  // Beside the clutter, outside the region's window: nothing pulls there.
  EXPECT_LT(BruteDistance(s.filled, 104, 9), 4);
  EXPECT_EQ(o.DistanceToForeground(104, 9), static_cast<float>(kTruncation));
  EXPECT_EQ(o.DistanceToForeground(-3, 40), static_cast<float>(kTruncation));
}

TEST(CameraObservation, LargeGapsStayOpen) {
  Scene s = MakeScene();
  const cv::Rect gap(40, 60, 9, 9);  // 81 pixels: more than max_hole_px
  s.mask(gap).setTo(0);
  const CameraObservation o(s.mask, s.region, kTruncation, 60);
  EXPECT_GT(o.DistanceToForeground(44, 64), 0.0f);
  EXPECT_EQ(o.DistanceToForeground(44, 42), 0.0f);  // the small hole is still filled
}

TEST(CameraObservation, NobodyOrNowhereGivesTheTruncation) {
  const cv::Mat empty = cv::Mat::zeros(60, 80, CV_8UC1);
  const CameraObservation nobody(empty, cv::Rect(0, 0, 80, 60), kTruncation, 60);
  const CameraObservation nowhere(MakeScene().mask, cv::Rect(500, 500, 10, 10), kTruncation, 60);
  const CameraObservation none;
  for (const CameraObservation* o : {&nobody, &nowhere, &none}) {
    EXPECT_EQ(o->region_count(), 0);
    for (float u : {-5.0f, 0.0f, 30.0f, 45.0f, 79.0f, 200.0f})
      EXPECT_EQ(o->DistanceToForeground(u, 40), static_cast<float>(o->truncation_px()));
  }
  EXPECT_EQ(nobody.Foreground(), 0);
  EXPECT_GT(nowhere.Foreground(), 0);
}

// Where someone else is drawn (several people tracked at once) the person pays nothing
// either way: those pixels leave the foreground to explain, count as foreground for the
// distance (against brute force over the mask with them set) and for the body's pixels
// outside the mask, and the caller's mask is untouched.
TEST(CameraObservation, PixelsOfOthersAreNeitherToExplainNorForbidden) {
  const Scene s = MakeScene();
  cv::Mat hidden = cv::Mat::zeros(s.mask.size(), CV_8UC1);
  cv::rectangle(hidden, cv::Rect(30, 50, 40, 25), cv::Scalar(255), cv::FILLED);  // over the legs and beyond
  const cv::Mat given = s.mask.clone();
  const CameraObservation o(s.mask, s.region, kTruncation, 60, hidden);
  EXPECT_EQ(cv::countNonZero(s.mask != given), 0);
  cv::Mat to_explain = s.filled.clone();
  to_explain.setTo(0, hidden);
  EXPECT_EQ(o.region_count(), cv::countNonZero(to_explain(s.region)));
  EXPECT_EQ(cv::countNonZero(o.mask() & hidden), 0);
  const cv::Mat drawable = s.filled | hidden;
  for (int v = s.region.y; v < s.region.br().y; v += 3)
    for (int u = s.region.x; u < s.region.br().x; u += 3)
      ASSERT_NEAR(o.DistanceToForeground(u, v), BruteDistance(drawable, u, v), 1e-4) << u << ", " << v;
  const cv::Mat grown = o.region_bits_grown().ToMat();
  EXPECT_EQ(cv::countNonZero(hidden & ~grown), 0);  // every hidden pixel may be drawn on
  // Without the hidden pixels nothing changes from the plain observation.
  const CameraObservation plain(s.mask, s.region, kTruncation, 60);
  const CameraObservation none(s.mask, s.region, kTruncation, 60, cv::Mat::zeros(s.mask.size(), CV_8UC1));
  EXPECT_EQ(none.region_count(), plain.region_count());
  EXPECT_EQ(cv::countNonZero(none.region_bits_grown().ToMat() != plain.region_bits_grown().ToMat()), 0);
}

}  // namespace
}  // namespace jgpm
