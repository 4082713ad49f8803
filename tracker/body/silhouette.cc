#include "tracker/body/silhouette.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <opencv2/imgproc.hpp>

#include "io/base/error.h"

namespace jgpm {
namespace {

constexpr int kShift = 4;  // fixed-point bits of the polygon coordinates (1/16 px)
constexpr double kOne = 1 << kShift;
constexpr double kNearMm = 100;
constexpr double kMaxSagittaPx = 0.15;  // chord-to-arc distance of the polygonal circles
constexpr double kOutlinePx = 0.5;
constexpr double kMaxOffImage = 4;  // parts further than this many image sizes away are not drawn

// The largest r at which r (1 + k1 r^2 + k2 r^4 + k3 r^6) / (1 + k4 r^2 + k5 r^4 + k6 r^6)
// still grows with r (capped at 10, 84 degrees off axis).
double MaxMonotoneRadius(const std::vector<double>& distortion) {
  auto k = [&](size_t i) { return i < distortion.size() ? distortion[i] : 0.0; };
  auto radial = [&](double r) {
    const double r2 = r * r;
    return r * (1 + r2 * (k(0) + r2 * (k(1) + r2 * k(4)))) / (1 + r2 * (k(5) + r2 * (k(6) + r2 * k(7))));
  };
  constexpr double kStep = 1e-3, kCap = 10;
  double previous = 0;
  for (double r = kStep; r <= kCap; r += kStep) {
    const double value = radial(r);
    if (!(value > previous)) return r - kStep;
    previous = value;
  }
  return kCap;
}

// Appends points of the arc of circle (centre, radius) of the capsule's round frame
// starting in unit direction `start` and turning by `span` (radians, negative: clockwise
// in image coordinates), both ends included, mapped to the image. Consecutive points are
// rotations of each other, so an arc costs two sines and cosines however many points it
// has (this runs for every part of every particle).
void AppendArc(const ImageCapsule& capsule, const Eigen::Vector2d& centre, double radius, Eigen::Vector2d start,
               double span, std::vector<cv::Point>* points) {
  // A circle smaller than the sagitta bound still gets three chords: a step just under
  // half a turn (not pi, which would give a full circle two). The bound holds on the
  // ellipse's longer axis.
  const double longest = radius * capsule.stretch;
  const double step =
      longest > kMaxSagittaPx ? 2 * std::acos(1 - kMaxSagittaPx / longest) : 3.14159;
  const int n = std::clamp(static_cast<int>(std::ceil(std::abs(span) / step)), 1, 32);
  const double c = std::cos(span / n), s = std::sin(span / n);
  Eigen::Vector2d direction = start;
  for (int i = 0; i <= n; ++i) {
    const Eigen::Vector2d p = capsule.Image(centre + radius * direction);
    points->emplace_back(static_cast<int>(std::lround(p.x() * kOne)), static_cast<int>(std::lround(p.y() * kOne)));
    direction = Eigen::Vector2d(c * direction.x() - s * direction.y(), s * direction.x() + c * direction.y());
  }
}

}  // namespace

CapsuleProjector::CapsuleProjector(const Camera& camera)
    : camera_(camera), focal_px_(0.5 * (camera.fx + camera.fy)), max_radius_(MaxMonotoneRadius(camera.distortion)) {}

bool CapsuleProjector::Project(const Capsule& capsule, ImageCapsule* image) const {
  const Eigen::Vector3d a = camera_.ToCamera(capsule.from_mm);
  const Eigen::Vector3d b = camera_.ToCamera(capsule.to_mm);
  if (!(a.z() >= kNearMm && b.z() >= kNearMm)) return false;  // also NaN
  const Eigen::Vector2d na = a.head<2>() / a.z(), nb = b.head<2>() / b.z();
  const double max_r2 = max_radius_ * max_radius_;
  if (na.squaredNorm() > max_r2 || nb.squaredNorm() > max_r2) return false;  // the lens would fold it back
  image->a = camera_.DistortToPixel(na);
  image->b = camera_.DistortToPixel(nb);
  const double limit_x = kMaxOffImage * camera_.width, limit_y = kMaxOffImage * camera_.height;
  auto in_range = [&](const Eigen::Vector2d& p) {
    return std::abs(p.x() - 0.5 * camera_.width) < limit_x && std::abs(p.y() - 0.5 * camera_.height) < limit_y;
  };
  if (!in_range(image->a) || !in_range(image->b)) return false;
  image->ra = std::min(limit_x, focal_px_ * capsule.radius_from_mm / a.z());
  image->rb = std::min(limit_x, focal_px_ * capsule.radius_to_mm / b.z());
  // 1 / cos(theta) of the capsule's middle, along the line from the principal point.
  image->lean = 0.5 * (na + nb);
  image->stretch = std::sqrt(1 + image->lean.squaredNorm());
  image->grow = 1 / (image->stretch + 1);
  image->shrink = image->grow / image->stretch;
  image->middle = 0.5 * (image->a + image->b);
  return image->ra >= 0 && image->rb >= 0;
}

SilhouetteRenderer::SilhouetteRenderer(const Camera& camera) : camera_(camera), projector_(camera) {}

cv::Rect SilhouetteRenderer::Render(const std::vector<Capsule>& capsules, cv::Mat* mask) const {
  mask->create(camera_.height, camera_.width, CV_8UC1);
  mask->setTo(0);
  return Draw(capsules, mask);
}

cv::Rect SilhouetteRenderer::Draw(const std::vector<Capsule>& capsules, cv::Mat* mask,
                                  std::vector<Eigen::Vector2f>* outline, double outline_step_px) const {
  JGPM_CHECK(mask->rows == camera_.height && mask->cols == camera_.width && mask->type() == CV_8UC1);
  thread_local std::vector<cv::Point> polygon;
  polygon.reserve(80);
  double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
  ImageCapsule image;
  for (const Capsule& capsule : capsules) {
    if (!projector_.Project(capsule, &image)) continue;
    // The hull of two circles in the capsule's round frame, mapped to the image.
    const Eigen::Vector2d ca = image.Round(image.a);
    const Eigen::Vector2d cb = image.Round(image.b);
    // OpenCV's fill also sets the pixels its outline passes through, about half a pixel
    // outside the polygon: shrink by that so the area matches the shape's.
    const double ra = std::max(0.0, image.ra - kOutlinePx);
    const double rb = std::max(0.0, image.rb - kOutlinePx);
    polygon.clear();
    const Eigen::Vector2d d = cb - ca;
    const double length = d.norm();
    if (length <= std::abs(ra - rb) + 1e-9) {
      // One end's circle holds the other: the hull is that circle.
      AppendArc(image, ra >= rb ? ca : cb, std::max(ra, rb), Eigen::Vector2d(1, 0), -2 * std::numbers::pi, &polygon);
      polygon.pop_back();
    } else {
      // Outer tangents touch the circles in directions +-n cos(phi) + u sin(phi) (u along
      // the axis, n its normal, sin(phi) = (ra - rb) / |d|), i.e. u turned by
      // +-(pi/2 - phi); walk clockwise: far side of b, then back side of a.
      const Eigen::Vector2d u = d / length, n(-u.y(), u.x());
      const double sin_phi = (ra - rb) / length, cos_phi = std::sqrt(1 - sin_phi * sin_phi);
      const double half = std::numbers::pi / 2 - std::asin(sin_phi);
      AppendArc(image, cb, rb, n * cos_phi + u * sin_phi, -2 * half, &polygon);
      AppendArc(image, ca, ra, -n * cos_phi + u * sin_phi, -(2 * std::numbers::pi - 2 * half), &polygon);
    }
    cv::fillConvexPoly(*mask, polygon, cv::Scalar(255), cv::LINE_8, kShift);
    if (outline) {
      // Along each edge of the closed polygon, points at most outline_step_px apart.
      for (size_t i = 0; i < polygon.size(); ++i) {
        const cv::Point& p = polygon[i];
        const cv::Point& q = polygon[(i + 1) % polygon.size()];
        const Eigen::Vector2f from(p.x / static_cast<float>(kOne), p.y / static_cast<float>(kOne));
        const Eigen::Vector2f to(q.x / static_cast<float>(kOne), q.y / static_cast<float>(kOne));
        const int steps = std::max(1, static_cast<int>(std::ceil((to - from).norm() / outline_step_px)));
        for (int k = 0; k < steps; ++k) outline->push_back(from + (to - from) * (static_cast<float>(k) / steps));
      }
    }
    const double r = std::max(ra, rb) * image.stretch + kOutlinePx;
    x0 = std::min({x0, image.a.x() - r, image.b.x() - r});
    y0 = std::min({y0, image.a.y() - r, image.b.y() - r});
    x1 = std::max({x1, image.a.x() + r, image.b.x() + r});
    y1 = std::max({y1, image.a.y() + r, image.b.y() + r});
  }
  if (x1 < x0) return {};
  const cv::Rect drawn(cv::Point(static_cast<int>(std::floor(x0)), static_cast<int>(std::floor(y0))),
                       cv::Point(static_cast<int>(std::ceil(x1)) + 1, static_cast<int>(std::ceil(y1)) + 1));
  return drawn & cv::Rect(0, 0, camera_.width, camera_.height);
}

}  // namespace jgpm
