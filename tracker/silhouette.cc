#include "tracker/silhouette.h"

#include <algorithm>
#include <cmath>

#include <opencv2/imgproc.hpp>

namespace jgpm {
namespace {

constexpr int kShift = 4;  // fixed-point bits of the polygon coordinates (1/16 px)
constexpr double kOne = 1 << kShift;
constexpr double kNearMm = 100;
constexpr double kMaxSagittaPx = 0.15;  // chord-to-arc distance of the polygonal circles
constexpr double kOutlinePx = 0.5;

// Appends points of the arc of circle (centre, radius) starting in unit direction `start`
// and turning by `span` (radians, negative: clockwise in image coordinates), both ends
// included. Consecutive points are rotations of each other, so an arc costs two sines
// and cosines however many points it has (this runs for every part of every particle).
void AppendArc(const Eigen::Vector2d& centre, double radius, Eigen::Vector2d start, double span,
               std::vector<cv::Point>* points) {
  const double step =
      radius > kMaxSagittaPx ? 2 * std::acos(1 - kMaxSagittaPx / radius) : 3.14159;
  const int n = std::clamp(static_cast<int>(std::ceil(std::abs(span) / step)), 1, 32);
  const double c = std::cos(span / n), s = std::sin(span / n);
  Eigen::Vector2d direction = start;
  for (int i = 0; i <= n; ++i) {
    const Eigen::Vector2d p = centre + radius * direction;
    points->emplace_back(static_cast<int>(std::lround(p.x() * kOne)), static_cast<int>(std::lround(p.y() * kOne)));
    direction = Eigen::Vector2d(c * direction.x() - s * direction.y(), s * direction.x() + c * direction.y());
  }
}

}  // namespace

SilhouetteRenderer::SilhouetteRenderer(const Camera& camera)
    : camera_(camera), focal_px_(0.5 * (camera.fx + camera.fy)) {}

cv::Rect SilhouetteRenderer::Render(const std::vector<Capsule>& capsules, cv::Mat* mask) const {
  mask->create(camera_.height, camera_.width, CV_8UC1);
  mask->setTo(0);
  std::vector<cv::Point> polygon;
  polygon.reserve(80);
  double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
  for (const Capsule& capsule : capsules) {
    const Eigen::Vector3d a = camera_.ToCamera(capsule.from_mm);
    const Eigen::Vector3d b = camera_.ToCamera(capsule.to_mm);
    if (a.z() < kNearMm || b.z() < kNearMm) continue;
    const Eigen::Vector2d ca = camera_.DistortToPixel(a.head<2>() / a.z());
    const Eigen::Vector2d cb = camera_.DistortToPixel(b.head<2>() / b.z());
    // OpenCV's fill also sets the pixels its outline passes through, about half a pixel
    // outside the polygon: shrink by that so the area matches the shape's.
    const double ra = std::max(0.0, focal_px_ * capsule.radius_from_mm / a.z() - kOutlinePx);
    const double rb = std::max(0.0, focal_px_ * capsule.radius_to_mm / b.z() - kOutlinePx);
    polygon.clear();
    const Eigen::Vector2d d = cb - ca;
    const double length = d.norm();
    if (length <= std::abs(ra - rb) + 1e-9) {
      // One end's circle holds the other: the hull is that circle.
      AppendArc(ra >= rb ? ca : cb, std::max(ra, rb), Eigen::Vector2d(1, 0), -2 * M_PI, &polygon);
      polygon.pop_back();
    } else {
      // Outer tangents touch the circles in directions +-n cos(phi) + u sin(phi) (u along
      // the axis, n its normal, sin(phi) = (ra - rb) / |d|), i.e. u turned by
      // +-(pi/2 - phi); walk clockwise: far side of b, then back side of a.
      const Eigen::Vector2d u = d / length, n(-u.y(), u.x());
      const double sin_phi = (ra - rb) / length, cos_phi = std::sqrt(1 - sin_phi * sin_phi);
      const double half = M_PI / 2 - std::asin(sin_phi);
      AppendArc(cb, rb, n * cos_phi + u * sin_phi, -2 * half, &polygon);
      AppendArc(ca, ra, -n * cos_phi + u * sin_phi, -(2 * M_PI - 2 * half), &polygon);
    }
    cv::fillConvexPoly(*mask, polygon, cv::Scalar(255), cv::LINE_8, kShift);
    const double r = std::max(ra, rb) + kOutlinePx;
    x0 = std::min({x0, ca.x() - r, cb.x() - r});
    y0 = std::min({y0, ca.y() - r, cb.y() - r});
    x1 = std::max({x1, ca.x() + r, cb.x() + r});
    y1 = std::max({y1, ca.y() + r, cb.y() + r});
  }
  if (x1 < x0) return {};
  const cv::Rect drawn(cv::Point(static_cast<int>(std::floor(x0)), static_cast<int>(std::floor(y0))),
                       cv::Point(static_cast<int>(std::ceil(x1)) + 1, static_cast<int>(std::ceil(y1)) + 1));
  return drawn & cv::Rect(0, 0, camera_.width, camera_.height);
}

}  // namespace jgpm
