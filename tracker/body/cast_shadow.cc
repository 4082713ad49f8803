#include "tracker/body/cast_shadow.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace jgpm {
namespace {

// A shadow piece's outline: arcs of at most kArcStepDeg between points (the chords' middles
// within 1 - cos(22.5 degrees) = 8% of the radius, a pixel for a thigh's shadow 12 px wide).
constexpr double kArcStepDeg = 45;
// A long shadow is drawn in pieces (interpolated spheres along the part) of at most this
// long on the floor, whose straight edges a lens bends by under a pixel.
constexpr double kPieceMm = 400;
// A foot's or a toe's shadow lies under it, within its own image, and a thumb's within the
// hand's: left out (6 of the tracker's 25 parts).
constexpr double kUnderFootMm = 150, kThinMm = 20;

// Calls `fill` with each piece's outline in pixels (convex, in order). On the floor a
// sphere's shadow is an ellipse, its radius across the light and 1 / sin(elevation) times
// it along; in the frame where the light's horizontal direction is squeezed by sin
// (elevation) those are circles, and a piece's shadow, the hull of its ends', is a flat
// capsule there: two arcs joined by the outer tangents, written out in order.
template <typename Fill>
void ForEachShadowPiece(const CapsuleProjector& projector, const std::vector<Capsule>& capsules,
                        const Eigen::Vector3d& light, double floor_mm, Fill&& fill) {
  if (!(light.y() > 1e-6)) return;
  const Eigen::Vector3d l = light.normalized();
  const Eigen::Vector2d horizontal(l.x(), l.z());
  if (horizontal.norm() < 1e-9) return;  // straight overhead: the shadow is under the body
  const Camera& camera = projector.camera();
  const double max_r2 = projector.max_normalised_radius() * projector.max_normalised_radius();
  const bool pinhole = std::all_of(camera.distortion.begin(), camera.distortion.end(), [](double k) { return k == 0; });
  // Floor directions across the light (w) and along it (h), and the squeeze along h.
  const Eigen::Vector2d h = horizontal.normalized(), w(-h.y(), h.x());
  const double squeeze = l.y();
  const auto cast = [&](const Eigen::Vector3d& p) {  // down the light to the floor: (x, z)
    const Eigen::Vector3d f = p - ((p.y() - floor_mm) / l.y()) * l;
    return Eigen::Vector2d(f.x(), f.z());
  };
  // Floor (x, z) from the squeezed frame's (across, along) and back.
  const auto to_squeezed = [&](const Eigen::Vector2d& f) { return Eigen::Vector2d(f.dot(w), f.dot(h) * squeeze); };
  const auto to_floor = [&](const Eigen::Vector2d& q) { return Eigen::Vector2d(q.x() * w + (q.y() / squeeze) * h); };
  constexpr int kMaxPoints = 2 * (360 / static_cast<int>(kArcStepDeg) + 2);
  cv::Point2f outline[kMaxPoints];
  for (const Capsule& c : capsules) {
    if (std::max(c.from_mm.y(), c.to_mm.y()) - floor_mm < kUnderFootMm ||
        std::max(c.radius_from_mm, c.radius_to_mm) < kThinMm)
      continue;
    const Eigen::Vector2d from = cast(c.from_mm), to = cast(c.to_mm);
    const int pieces = 1 + static_cast<int>(std::min((to - from).norm() / kPieceMm, 20.0));
    for (int k = 0; k < pieces; ++k) {
      const double t0 = double(k) / pieces, t1 = double(k + 1) / pieces;
      const Eigen::Vector2d a = to_squeezed(from + t0 * (to - from)), b = to_squeezed(from + t1 * (to - from));
      const double ra = c.radius_from_mm + t0 * (c.radius_to_mm - c.radius_from_mm);
      const double rb = c.radius_from_mm + t1 * (c.radius_to_mm - c.radius_from_mm);
      // The arcs: (centre, radius, first angle, span), in the squeezed frame.
      struct Arc {
        Eigen::Vector2d centre;
        double radius, first, span;
      } arcs[2];
      int n_arcs = 0;
      const Eigen::Vector2d d = b - a;
      const double length = d.norm();
      if (length <= std::abs(ra - rb) + 1e-9) {  // one end's circle holds the other's
        arcs[n_arcs++] = ra >= rb ? Arc{a, ra, 0, 2 * std::numbers::pi} : Arc{b, rb, 0, 2 * std::numbers::pi};
      } else {
        // The outer tangents touch at angles axis +- (90 degrees - phi), sin(phi) = (ra - rb) / |d|.
        const double axis = std::atan2(d.y(), d.x()), phi = std::asin((ra - rb) / length);
        const double ta = axis + 0.5 * std::numbers::pi - phi;
        arcs[n_arcs++] = {a, ra, ta, std::numbers::pi + 2 * phi};                             // a's far side
        arcs[n_arcs++] = {b, rb, axis - 0.5 * std::numbers::pi + phi, std::numbers::pi - 2 * phi};  // b's
      }
      int n = 0;
      bool dropped = false;
      for (int i = 0; i < n_arcs && !dropped; ++i) {
        const Arc& arc = arcs[i];
        const int steps = std::max(1, static_cast<int>(std::ceil(arc.span / (kArcStepDeg * std::numbers::pi / 180))));
        // The arc's points by turning the first (one sine and cosine per arc).
        const double step = arc.span / steps;
        const double cs = std::cos(step), sn = std::sin(step);
        Eigen::Vector2d radial = arc.radius * Eigen::Vector2d(std::cos(arc.first), std::sin(arc.first));
        const bool whole = arc.span >= 2 * std::numbers::pi - 1e-9;  // a whole circle: no point twice
        for (int j = 0; j <= steps - whole && !dropped; ++j) {
          const Eigen::Vector2d f = to_floor(arc.centre + radial);
          radial = Eigen::Vector2d(cs * radial.x() - sn * radial.y(), sn * radial.x() + cs * radial.y());
          const Eigen::Vector3d q = camera.ToCamera(Eigen::Vector3d(f.x(), floor_mm, f.y()));
          // Behind the camera, or where the lens would fold it back.
          if (!(q.z() > 1) || q.x() * q.x() + q.y() * q.y() > max_r2 * q.z() * q.z()) {
            dropped = true;
            break;
          }
          const Eigen::Vector2d pixel =
              pinhole ? Eigen::Vector2d(camera.fx * q.x() / q.z() + camera.cx, camera.fy * q.y() / q.z() + camera.cy)
                      : camera.DistortToPixel(q.head<2>() / q.z());
          outline[n++] = cv::Point2f(static_cast<float>(pixel.x()), static_cast<float>(pixel.y()));
        }
      }
      if (!dropped && n >= 3) fill(outline, n);
    }
  }
}

}  // namespace

void DrawCastShadow(const CapsuleProjector& projector, const std::vector<Capsule>& capsules,
                    const Eigen::Vector3d& light, double floor_mm, const cv::Rect& clip, BitMask* mask) {
  const cv::Rect box = clip & cv::Rect(0, 0, mask->width(), mask->height());
  if (box.empty()) return;
  ForEachShadowPiece(projector, capsules, light, floor_mm, [&](const cv::Point2f* hull, int n) {
    float top = hull[0].y, bottom = hull[0].y;
    for (int i = 1; i < n; ++i) top = std::min(top, hull[i].y), bottom = std::max(bottom, hull[i].y);
    // Rows whose pixel centres lie within the hull's rows, and in each the span of centres
    // between its edges (a pixel is in when its centre is, as for the bodies).
    const int v0 = std::max(box.y, static_cast<int>(std::ceil(std::max(top, -1e6f))));
    const int v1 = std::min(box.y + box.height - 1, static_cast<int>(std::floor(std::min(bottom, 1e6f))));
    for (int v = v0; v <= v1; ++v) {
      float left = 1e30f, right = -1e30f;
      for (int i = 0; i < n; ++i) {
        const cv::Point2f& p = hull[i];
        const cv::Point2f& q = hull[(i + 1) % n];
        if ((v < p.y && v < q.y) || (v > p.y && v > q.y)) continue;
        const float x = p.y == q.y ? std::min(p.x, q.x) : p.x + (v - p.y) * (q.x - p.x) / (q.y - p.y);
        const float x_other = p.y == q.y ? std::max(p.x, q.x) : x;
        left = std::min(left, x), right = std::max(right, x_other);
      }
      const int x0 = std::max(box.x, static_cast<int>(std::ceil(std::max(left, -1e6f))));
      const int x1 = std::min(box.x + box.width - 1, static_cast<int>(std::floor(std::min(right, 1e6f))));
      if (x1 >= x0) mask->SetSpan(v, x0, x1);
    }
  });
}

}  // namespace jgpm
