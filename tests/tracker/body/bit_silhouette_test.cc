// The packed-bit renderer against a brute-force oracle: a pixel is set exactly when its
// centre lies in the convex hull of the capsule's two projected end ellipses, i.e. when,
// in the capsule's round frame (ImageCapsule::Round, where the ellipses are discs),
// min over t in [0, 1] of |p - (a + t (b - a))| - (ra + t (rb - ra)) <= 0 (a convex
// function of t, minimised by golden-section search). Pixels within 1e-6 px of the
// boundary may go either way.
#include "tracker/body/bit_silhouette.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

namespace jgpm {
namespace {

double HullDistance(const ImageCapsule& c, double u, double v) {
  const Eigen::Vector2d p = c.Round(Eigen::Vector2d(u, v)), a = c.Round(c.a), b = c.Round(c.b);
  auto f = [&](double t) { return (p - (a + t * (b - a))).norm() - (c.ra + t * (c.rb - c.ra)); };
  double lo = 0, hi = 1;
  const double g = (std::sqrt(5.0) - 1) / 2;
  for (int i = 0; i < 60; ++i) {
    const double m1 = hi - g * (hi - lo), m2 = lo + g * (hi - lo);
    if (f(m1) < f(m2)) hi = m2; else lo = m1;
  }
  return std::min({f(0), f(1), f(0.5 * (lo + hi))});
}

Camera TestCamera() {
  Camera camera = LookAtCamera("c", 200, 150, 180, Eigen::Vector3d(0, 1000, -4000), Eigen::Vector3d(0, 900, 0));
  camera.distortion = {-0.05, 0.01, 0, 0, 0};
  return camera;
}

TEST(BitSilhouette, EveryPixelAgreesWithTheHullOracle) {
  const Camera camera = TestCamera();
  const CapsuleProjector projector(camera);
  const BitSilhouetteRenderer renderer(camera);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> x(-1500, 1500), y(-200, 2200), z(-1500, 1500), r(5, 250);
  int drawn = 0, compared_in = 0, stretched = 0;
  for (int trial = 0; trial < 300; ++trial) {
    Capsule capsule{{x(rng), y(rng), z(rng)}, {x(rng), y(rng), z(rng)}, r(rng), r(rng)};
    if (trial % 10 == 0) capsule.to_mm = capsule.from_mm + Eigen::Vector3d(0, 0.5, 0);  // one disc in the other
    if (trial % 10 == 1) capsule.to_mm.y() = capsule.from_mm.y();                       // a horizontal-ish limb
    ImageCapsule image;
    if (!projector.Project(capsule, &image)) continue;
    ++drawn;
    stretched += image.stretch > 1.03;
    const double reach_a = image.ra * image.stretch, reach_b = image.rb * image.stretch;
    BitMask mask(camera.width, camera.height);
    renderer.Draw({capsule}, &mask);
    const cv::Mat drawn_mat = mask.ToMat();
    // Outside the hull's bounding box (plus a pixel) nothing may be set; inside it, each
    // pixel is compared with the oracle.
    const int u0 = std::max(0, static_cast<int>(std::floor(std::min(image.a.x() - reach_a, image.b.x() - reach_b))) - 1);
    const int u1 = std::min(camera.width - 1, static_cast<int>(std::ceil(std::max(image.a.x() + reach_a, image.b.x() + reach_b))) + 1);
    const int w0 = std::max(0, static_cast<int>(std::floor(std::min(image.a.y() - reach_a, image.b.y() - reach_b))) - 1);
    const int w1 = std::min(camera.height - 1, static_cast<int>(std::ceil(std::max(image.a.y() + reach_a, image.b.y() + reach_b))) + 1);
    int rows_min = camera.height, rows_max = -1, set_in_box = 0;
    for (int v = w0; v <= w1; ++v) {
      for (int u = u0; u <= u1; ++u) {
        const bool set = drawn_mat.at<uint8_t>(v, u) != 0;
        set_in_box += set;
        if (set) rows_min = std::min(rows_min, v), rows_max = std::max(rows_max, v);
        const double d = HullDistance(image, u, v);
        if (std::abs(d) < 1e-6) continue;
        compared_in += d < 0;
        ASSERT_EQ(set, d < 0) << "trial " << trial << " pixel (" << u << ", " << v << ") hull distance " << d;
      }
    }
    EXPECT_EQ(set_in_box, cv::countNonZero(drawn_mat)) << "pixels set outside the hull's box, trial " << trial;
    // The rows the mask says it touched hold every set pixel, and Clear blanks it.
    if (rows_max >= 0) {
      EXPECT_LE(mask.first_row(), rows_min);
      EXPECT_GE(mask.last_row(), rows_max + 1);
    }
    mask.Clear();
    EXPECT_EQ(mask.Count(), 0);
  }
  EXPECT_GT(drawn, 100);
  EXPECT_GT(compared_in, 10000);
  EXPECT_GT(stretched, 30);  // ellipses, not only circles near the axis
}

TEST(BitSilhouette, SpansAreClippedToTheImage) {
  BitMask mask(70, 3);
  mask.SetSpan(1, -5, 200);
  mask.SetSpan(-1, 0, 10);
  mask.SetSpan(3, 0, 10);
  mask.SetSpan(0, 10, 9);
  EXPECT_EQ(mask.Count(), 70);
  EXPECT_EQ(mask.first_row(), 1);
  EXPECT_EQ(mask.last_row(), 2);
  mask.SetSpanUnchecked(2, 63, 64);
  mask.Mark(2, 2, 63, 64);
  EXPECT_EQ(mask.Count(), 72);
  EXPECT_EQ(mask.last_row(), 3);
}

TEST(BitSilhouette, SinCosMatchesLibmUpToPi) {
  double worst = 0;
  for (int i = -2000; i <= 2000; ++i) {
    const double x = std::numbers::pi * i / 2000;
    double s, c;
    SinCos(x, &s, &c);
    worst = std::max({worst, std::abs(s - std::sin(x)), std::abs(c - std::cos(x))});
  }
  EXPECT_LT(worst, 1e-13);
}

// Counting and clearing use the box of words a mask was drawn in: a span at either end of
// a row, then the grown mask against a per-pixel dilation.
TEST(BitSilhouette, TheTouchedWordsHoldEveryPixelAndDilateLikeOpenCv) {
  BitMask mask(200, 6);
  mask.SetSpan(2, 0, 0);
  mask.SetSpan(3, 127, 128);
  EXPECT_EQ(mask.first_word(), 0);
  EXPECT_EQ(mask.last_word(), 3);
  mask.Clear();
  mask.SetSpan(1, 64, 64);
  mask.SetSpan(4, 191, 199);
  EXPECT_EQ(mask.first_word(), 1);
  EXPECT_EQ(mask.last_word(), 4);
  EXPECT_EQ(mask.Count(), 10);
  BitMask grown;
  mask.DilateInto(&grown);
  cv::Mat expected;
  cv::dilate(mask.ToMat(), expected, cv::Mat::ones(3, 3, CV_8U));
  EXPECT_EQ(cv::countNonZero(grown.ToMat() != expected), 0);
  EXPECT_EQ(grown.first_word(), 0);  // pixel 64's neighbour 63 is in word 0
  mask.Clear();
  EXPECT_EQ(mask.Count(), 0);
  EXPECT_EQ(cv::countNonZero(mask.ToMat()), 0);
}

}  // namespace
}  // namespace jgpm
