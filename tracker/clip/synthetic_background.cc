#include "tracker/clip/synthetic_background.h"

#include <cmath>
#include <cstdint>

#include <opencv2/core.hpp>

namespace jgpm {
namespace {

constexpr double kTileMm = 600, kGroutMm = 12, kPanelMm = 700;

// A repeatable pseudo-random value in [0, 1) per integer cell.
double Hash(int64_t a, int64_t b) {
  uint64_t h = static_cast<uint64_t>(a) * 0x9E3779B97F4A7C15ull ^ static_cast<uint64_t>(b) * 0xC2B2AE3D27D4EB4Full;
  h ^= h >> 31;
  h *= 0xBF58476D1CE4E5B9ull;
  h ^= h >> 29;
  return static_cast<double>(h >> 11) / 9007199254740992.0;
}

// Colour (B, G, R in [0, 255]) seen along one ray.
Eigen::Vector3d Shade(const Eigen::Vector3d& origin, const Eigen::Vector3d& ray,
                      const Eigen::Vector3d& centre, double radius, double wall_height) {
  // Walls: |(o + t d - c)_xz| = radius, the camera inside.
  const Eigen::Vector2d o(origin.x() - centre.x(), origin.z() - centre.z()), d(ray.x(), ray.z());
  const double a = d.squaredNorm(), b = o.dot(d), c = o.squaredNorm() - radius * radius;
  const double t_wall = a > 1e-12 ? (-b + std::sqrt(std::max(0.0, b * b - a * c))) / a : 1e12;
  const double t_floor = ray.y() < -1e-9 ? -origin.y() / ray.y() : 1e12;
  if (t_floor < t_wall) {
    const Eigen::Vector3d p = origin + t_floor * ray;
    const double fx = p.x() / kTileMm, fz = p.z() / kTileMm;
    const double gx = (fx - std::floor(fx)) * kTileMm, gz = (fz - std::floor(fz)) * kTileMm;
    if (gx < kGroutMm || gz < kGroutMm) return {95, 100, 105};
    const double v = Hash(static_cast<int64_t>(std::floor(fx)), static_cast<int64_t>(std::floor(fz)));
    return Eigen::Vector3d(150, 165, 180) * (0.8 + 0.35 * v);  // beige tiles
  }
  const Eigen::Vector3d p = origin + t_wall * ray;
  if (p.y() > wall_height) return {205, 205, 200};  // ceiling
  if (p.y() < 120) return {60, 65, 70};                // skirting board
  const double angle = std::atan2(p.z() - centre.z(), p.x() - centre.x());
  const double s = angle * radius / kPanelMm;
  const int64_t panel = static_cast<int64_t>(std::floor(s));
  const double v = Hash(panel, 7);
  // Panels in a few muted colours, with a dark seam and a picture on some of them.
  if (s - std::floor(s) < 0.03) return {70, 75, 80};
  const double u = s - std::floor(s), h = p.y() / wall_height;
  if (v > 0.6 && u > 0.2 && u < 0.8 && h > 0.45 && h < 0.75)
    return Eigen::Vector3d(60 + 150 * Hash(panel, 1), 60 + 150 * Hash(panel, 2), 60 + 150 * Hash(panel, 3));
  const Eigen::Vector3d colours[3] = {{170, 190, 200}, {150, 170, 150}, {190, 180, 175}};
  return colours[static_cast<int>(v * 3) % 3] * (0.9 + 0.1 * h);
}

}  // namespace

cv::Mat RenderBackground(const Camera& camera, const Eigen::Vector3d& room_centre_mm,
                         double room_radius_mm, double wall_height_mm) {
  const int w = camera.width, h = camera.height;
  Eigen::Matrix2Xd pixels(2, 4 * static_cast<Eigen::Index>(w) * h);
  for (int v = 0; v < h; ++v)
    for (int u = 0; u < w; ++u)
      for (int s = 0; s < 4; ++s)
        pixels.col(4 * (v * w + u) + s) << u - 0.25 + 0.5 * (s % 2), v - 0.25 + 0.5 * (s / 2);
  const Eigen::Matrix3Xd rays = camera.PixelRaysInWorld(pixels);
  const Eigen::Vector3d origin = camera.CentreInWorld();
  cv::Mat image(h, w, CV_8UC3);
  for (int v = 0; v < h; ++v)
    for (int u = 0; u < w; ++u) {
      Eigen::Vector3d sum = Eigen::Vector3d::Zero();
      for (int s = 0; s < 4; ++s)
        sum += Shade(origin, rays.col(4 * (v * w + u) + s), room_centre_mm, room_radius_mm, wall_height_mm);
      const Eigen::Vector3d c = sum / 4;
      image.at<cv::Vec3b>(v, u) = cv::Vec3b(cv::saturate_cast<uchar>(c[0]), cv::saturate_cast<uchar>(c[1]),
                                            cv::saturate_cast<uchar>(c[2]));
    }
  return image;
}

}  // namespace jgpm
