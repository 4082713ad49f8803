// Head and foot points from masks drawn with known shapes: upright rectangles (walkers)
// whose top edge and lowest 30%'s centroid are known exactly, moving across the image; a
// wide blob (a car), a blob cut by the image's edge and a walker seen for a moment, which
// must not count.
#include "tracker/frames/walker_points.h"

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

namespace jgpm {
namespace {

// Columns x-a .. x+a, rows y-b .. y+b.
void Draw(cv::Mat* mask, double x, double y, int a, int b) {
  const int cx = static_cast<int>(x), cy = static_cast<int>(y);
  cv::rectangle(*mask, cv::Point(cx - a, cy - b), cv::Point(cx + a, cy + b), 255, cv::FILLED);
}

TEST(WalkerPointFinder, FindsEachWalkersHeadAndFeetAndKeepsTheirIdentity) {
  WalkerPointFinder finder(320, 240);
  for (int frame = 0; frame < 30; ++frame) {
    cv::Mat mask(240, 320, CV_8UC1, cv::Scalar(0));
    Draw(&mask, 40 + 3 * frame, 100, 10, 40);    // walker A: rows 60..140, moving right
    Draw(&mask, 280 - 2 * frame, 160, 8, 30);    // walker B: rows 130..190, moving left
    Draw(&mask, 160, 215, 40, 10);               // a car: wider than tall
    Draw(&mask, 2, 100, 10, 40);                 // cut by the left edge
    if (frame < 3) Draw(&mask, 200, 60, 5, 20);  // seen for a moment
    finder.Add(mask);
  }
  const std::vector<HeadFoot> points = finder.Points();
  ASSERT_EQ(points.size(), 60u);
  int a = 0, b = 0;
  for (const HeadFoot& point : points) {
    ASSERT_TRUE(point.walker == 0 || point.walker == 1);
    const bool is_a = point.head_px.y() < 100;
    const int walker_a = points[0].head_px.y() < 100 ? points[0].walker : 1 - points[0].walker;
    EXPECT_EQ(point.walker == walker_a, is_a);
    // Head: the top row's edge, half a pixel above it. Foot: the mean row of the lowest
    // round(0.3 * rows).
    if (is_a) {  // rows 60..140 (81): the lowest 24 are 117..140
      ++a;
      EXPECT_DOUBLE_EQ(point.head_px.y(), 59.5);
      EXPECT_DOUBLE_EQ(point.foot_px.y(), (117 + 140) / 2.0);
    } else {  // rows 130..190 (61): the lowest 18 are 173..190
      ++b;
      EXPECT_DOUBLE_EQ(point.head_px.y(), 129.5);
      EXPECT_DOUBLE_EQ(point.foot_px.y(), (173 + 190) / 2.0);
    }
    EXPECT_DOUBLE_EQ(point.head_px.x(), point.foot_px.x());  // upright
    // The frame, from where the walker was drawn then.
    const double x0 = is_a ? 40 : 280, speed = is_a ? 3 : -2;
    EXPECT_NEAR(point.head_px.x(), x0 + speed * point.frame, 0.5) << point.frame;
  }
  EXPECT_EQ(a, 30);
  EXPECT_EQ(b, 30);
  // Each walker's column is its centre's.
  EXPECT_DOUBLE_EQ(points[0].head_px.x() + points[1].head_px.x(), 40 + 280);
  EXPECT_EQ(finder.frames(), 30);
}

TEST(WalkerPointFinder, AWalkerHiddenTooLongComesBackAsAnother) {
  WalkerPointOptions options;
  options.min_frames = 1;
  WalkerPointFinder finder(320, 240, options);
  for (int frame = 0; frame < 20; ++frame) {
    cv::Mat mask(240, 320, CV_8UC1, cv::Scalar(0));
    if (frame < 5 || frame >= 5 + options.max_gap_frames + 1) Draw(&mask, 100 + frame, 120, 10, 40);
    if (frame == 3) {
      finder.Skip();  // a frame the video lost: the clock moves on
      continue;
    }
    finder.Add(mask);
  }
  EXPECT_EQ(finder.frames(), 20);
  const auto points = finder.Points();
  ASSERT_FALSE(points.empty());
  EXPECT_EQ(points.front().walker, 0);
  EXPECT_EQ(points.back().walker, 1);
  for (const HeadFoot& point : points) {
    EXPECT_NE(point.frame, 3);
    EXPECT_NEAR(point.head_px.x(), 100 + point.frame, 0.5);
  }
}

}  // namespace
}  // namespace jgpm
