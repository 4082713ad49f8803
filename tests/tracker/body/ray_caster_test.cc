// The exact renderer against brute force: a tapered capsule is the union of the spheres
// interpolated between its ends, so a point is inside iff min over lambda of
// |p - c(lambda)| - r(lambda) <= 0 (convex in lambda). Ray entries found by marching and
// bisecting that function must match the analytic intersection.
#include "tracker/body/ray_caster.h"

#include <cmath>
#include <limits>
#include <numbers>
#include <random>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

namespace jgpm {
namespace {

// min over lambda of |p - c(lambda)| - r(lambda) and the minimising centre.
double HullDistance(const Capsule& c, const Eigen::Vector3d& p, Eigen::Vector3d* nearest_centre) {
  auto f = [&](double l) {
    return (p - (c.from_mm + l * (c.to_mm - c.from_mm))).norm() -
           (c.radius_from_mm + l * (c.radius_to_mm - c.radius_from_mm));
  };
  double lo = 0, hi = 1;
  for (int i = 0; i < 70; ++i) {  // ternary search on a convex function
    const double m1 = lo + (hi - lo) / 3, m2 = hi - (hi - lo) / 3;
    (f(m1) < f(m2) ? hi : lo) = f(m1) < f(m2) ? m2 : m1;
  }
  const double l = 0.5 * (lo + hi);
  if (nearest_centre) *nearest_centre = c.from_mm + l * (c.to_mm - c.from_mm);
  return f(l);
}

TEST(IntersectCapsuleTest, MatchesBruteForceEntryAndNormal) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  int hits = 0, misses = 0, checked = 0;
  for (int trial = 0; trial < 1500; ++trial) {
    Capsule c;
    c.from_mm = 200 * Eigen::Vector3d(u(rng), u(rng), u(rng));
    c.to_mm = trial % 10 == 0 ? Eigen::Vector3d(c.from_mm + 10 * Eigen::Vector3d(u(rng), u(rng), u(rng)))
                              : Eigen::Vector3d(200 * Eigen::Vector3d(u(rng), u(rng), u(rng)));
    c.radius_from_mm = 60 + 50 * u(rng);
    c.radius_to_mm = 60 + 50 * u(rng);
    const Eigen::Vector3d origin = 2000 * Eigen::Vector3d(u(rng), u(rng), u(rng)).normalized();
    // Aim near the capsule; every 7th ray along its axis (inside the double cone).
    Eigen::Vector3d target = 0.5 * (c.from_mm + c.to_mm) + 250 * Eigen::Vector3d(u(rng), u(rng), u(rng));
    Eigen::Vector3d start = origin;
    if (trial % 7 == 0) {
      start = c.from_mm - 3 * (c.to_mm - c.from_mm) + Eigen::Vector3d(u(rng), u(rng), u(rng));
      target = c.to_mm;
    }
    const Eigen::Vector3d direction = (target - start).normalized();
    // March (1 mm) through the capsule's bounding sphere to the first inside point, then
    // bisect.
    const Eigen::Vector3d mid = 0.5 * (c.from_mm + c.to_mm) - start;
    const double bound = 0.5 * (c.to_mm - c.from_mm).norm() + std::max(c.radius_from_mm, c.radius_to_mm) + 2;
    const double along = mid.dot(direction), h = bound * bound - (mid.squaredNorm() - along * along);
    if (h < 0) continue;
    double entry = -1, closest = 1e300;
    for (double t = std::max(0.0, along - std::sqrt(h)); t < along + std::sqrt(h); t += 1.0) {
      const double g = HullDistance(c, start + t * direction, nullptr);
      closest = std::min(closest, g);
      if (g <= 0) {
        double lo = std::max(0.0, t - 1.0), hi = t;
        if (t == 0) { entry = 0; break; }
        for (int i = 0; i < 60; ++i) {
          const double mid = 0.5 * (lo + hi);
          (HullDistance(c, start + mid * direction, nullptr) <= 0 ? hi : lo) = mid;
        }
        entry = hi;
        break;
      }
    }
    if (std::abs(closest) < 0.05) continue;  // grazing: a 1 mm march cannot decide it
    double t;
    Eigen::Vector3d normal;
    const bool hit = IntersectCapsule(start, direction, c, &t, &normal);
    ASSERT_EQ(hit, entry >= 0) << "trial " << trial << " closest " << closest;
    ++checked;
    if (!hit) {
      ++misses;
      continue;
    }
    ++hits;
    EXPECT_NEAR(t, entry, 1e-6 * std::max(1.0, entry)) << "trial " << trial;
    if (t > 0) {
      Eigen::Vector3d centre;
      const Eigen::Vector3d p = start + t * direction;
      EXPECT_NEAR(HullDistance(c, p, &centre), 0, 1e-6);
      EXPECT_GT(normal.dot((p - centre).normalized()), 1 - 1e-6) << "trial " << trial;
    }
  }
  std::printf("%d rays checked: %d hits, %d misses\n", checked, hits, misses);
  EXPECT_GT(hits, 300);
  EXPECT_GT(misses, 100);
}

TEST(RayCasterTest, SphereOnTheAxisImagesAsTheRightCircle) {
  const Camera camera = LookAtCamera("c", 320, 240, 300, {0, 1000, -3000}, {0, 1000, 0});
  const RayCaster caster(camera);
  Capsule sphere{{0, 1000, 0}, {0, 1000, 0}, 200, 200};
  BodyImage image;
  caster.Render({sphere}, &image);
  // Its image is a circle of radius f r / sqrt(D^2 - r^2) about the principal point.
  const double radius = 300 * 200 / std::sqrt(3000.0 * 3000 - 200 * 200);
  const double area = cv::countNonZero(image.Mask());
  EXPECT_NEAR(area, std::numbers::pi * radius * radius, 2 * std::numbers::pi * radius * 0.5);
  const cv::Rect box = cv::boundingRect(image.Mask());
  EXPECT_NEAR(box.x + (box.width - 1) / 2.0, camera.cx, 0.51);
  EXPECT_NEAR(box.width, 2 * radius, 1.01);
  // Depth at the centre: D - r; the normal there faces the camera.
  const int cu = 159, cv_ = 119;
  EXPECT_NEAR(image.depth_mm.at<float>(cv_, cu), 2800, 1.0);
  EXPECT_LT(image.normal.at<cv::Vec3f>(cv_, cu)[2], -0.99);
}

TEST(RayCasterTest, NearerPartHidesTheFartherOne) {
  const Camera camera = LookAtCamera("c", 160, 120, 150, {0, 0, -3000}, {0, 0, 0});
  const RayCaster caster(camera);
  const Capsule far{{-400, 0, 0}, {400, 0, 0}, 100, 100};
  const Capsule near{{0, -400, -500}, {0, 400, -500}, 80, 80};
  BodyImage image;
  caster.Render({far, near}, &image);
  EXPECT_EQ(image.part.at<uint8_t>(60, 80), 1);  // the crossing: the near bar
  EXPECT_EQ(image.part.at<uint8_t>(60, 65), 0);  // the far bar alone
  EXPECT_EQ(image.part.at<uint8_t>(5, 5), BodyImage::kNoPart);
  EXPECT_NEAR(image.depth_mm.at<float>(60, 80), 2500 - 80, 1.0);
}

TEST(RayCasterTest, FollowsTheLensDistortion) {
  // A distorted camera sees each body point at the pixel Project gives it.
  Camera camera = LookAtCamera("c", 320, 240, 260, {300, 1200, -3500}, {0, 900, 0});
  camera.distortion = {-0.3, 0.1, 0.001, -0.002, 0};
  const RayCaster caster(camera);
  for (const Eigen::Vector3d& p : {Eigen::Vector3d(800, 1500, 200), Eigen::Vector3d(-900, 300, -100)}) {
    Eigen::Vector2d pixel;
    ASSERT_TRUE(camera.Project(p, &pixel));
    BodyImage image;
    caster.Render({Capsule{p, p, 40, 40}}, &image);
    const cv::Moments m = cv::moments(image.Mask(), true);
    ASSERT_GT(m.m00, 5);
    EXPECT_NEAR(m.m10 / m.m00, pixel.x(), 0.3);
    EXPECT_NEAR(m.m01 / m.m00, pixel.y(), 0.3);
  }
}

// What Render must give: every pixel's ray tried against every part, nearest hit kept.
BodyImage EveryPixel(const RayCaster& caster, const std::vector<Capsule>& capsules) {
  const Camera& camera = caster.camera();
  BodyImage image;
  image.part = cv::Mat(camera.height, camera.width, CV_8UC1, cv::Scalar(BodyImage::kNoPart));
  image.depth_mm = cv::Mat::zeros(camera.height, camera.width, CV_32FC1);
  image.normal = cv::Mat::zeros(camera.height, camera.width, CV_32FC3);
  for (int v = 0; v < camera.height; ++v)
    for (int u = 0; u < camera.width; ++u) {
      const Eigen::Vector3d ray = caster.rays().col(v * camera.width + u);
      double nearest = std::numeric_limits<double>::infinity();
      for (size_t i = 0; i < capsules.size(); ++i) {
        double t;
        Eigen::Vector3d n;
        if (!IntersectCapsule(caster.centre_in_world_mm(), ray, capsules[i], &t, &n) || t >= nearest) continue;
        nearest = t;
        image.part.at<uint8_t>(v, u) = static_cast<uint8_t>(i);
        image.depth_mm.at<float>(v, u) = static_cast<float>(t);
        image.normal.at<cv::Vec3f>(v, u) = cv::Vec3f(n.x(), n.y(), n.z());
      }
    }
  return image;
}

TEST(RayCasterTest, TilesGiveWhatEveryPixelGives) {
  // Random bodies of 20 parts before a wide distorted webcam, a long lens far away, and a
  // camera inside a part; image sizes that are not multiples of the tile.
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1, 1);
  Camera wide = LookAtCamera("wide", 331, 247, 150, {200, 1200, -1500}, {0, 900, 0});
  wide.distortion = {-0.25, 0.06, 0.001, -0.001, 0};
  const Camera far = LookAtCamera("far", 200, 150, 900, {3000, 5000, -12000}, {0, 900, 0});
  const Camera inside = LookAtCamera("inside", 96, 80, 60, {0, 900, 0}, {0, 900, 1000});
  int drawn = 0;
  for (const Camera& camera : {wide, far, inside}) {
    const RayCaster caster(camera);
    for (int body = 0; body < 4; ++body) {
      std::vector<Capsule> capsules;
      for (int i = 0; i < 20; ++i) {
        Capsule c;
        c.from_mm = Eigen::Vector3d(600 * u(rng), 900 + 800 * u(rng), 600 * u(rng));
        c.to_mm = c.from_mm + 300 * Eigen::Vector3d(u(rng), u(rng), u(rng));
        c.radius_from_mm = 60 + 50 * u(rng);
        c.radius_to_mm = 60 + 50 * u(rng);
        capsules.push_back(c);
      }
      BodyImage tiled;
      caster.Render(capsules, &tiled);
      const BodyImage expected = EveryPixel(caster, capsules);
      drawn += cv::countNonZero(expected.Mask());
      EXPECT_EQ(cv::norm(tiled.part, expected.part, cv::NORM_INF), 0) << camera.name << " body " << body;
      EXPECT_EQ(cv::norm(tiled.depth_mm, expected.depth_mm, cv::NORM_INF), 0) << camera.name << " body " << body;
      EXPECT_EQ(cv::norm(tiled.normal, expected.normal, cv::NORM_INF), 0) << camera.name << " body " << body;
    }
  }
  EXPECT_GT(drawn, 10000);  // the bodies were in view
}

}  // namespace
}  // namespace jgpm
