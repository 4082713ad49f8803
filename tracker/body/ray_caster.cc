#include "tracker/body/ray_caster.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <opencv2/core.hpp>

#include "io/base/error.h"

namespace jgpm {

bool IntersectCapsule(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction,
                      const Capsule& capsule, double* t_hit, Eigen::Vector3d* normal) {
  const Eigen::Vector3d& pa = capsule.from_mm;
  const Eigen::Vector3d& pb = capsule.to_mm;
  double ra = capsule.radius_from_mm, rb = capsule.radius_to_mm;
  const Eigen::Vector3d ba = pb - pa;
  const Eigen::Vector3d oa = origin - pa;
  const Eigen::Vector3d ob = origin - pb;
  const double rr = ra - rb;
  const double m0 = ba.dot(ba);
  double best = std::numeric_limits<double>::infinity();
  Eigen::Vector3d best_normal = Eigen::Vector3d::Zero();
  // Entry into a sphere, if ahead of the origin (or the origin inside it).
  auto sphere = [&](const Eigen::Vector3d& oc, double r) {
    const double b = oc.dot(direction);
    const double h = b * b - oc.dot(oc) + r * r;
    if (h < 0) return;
    const double t = std::max(0.0, -b - std::sqrt(h));
    if (-b + std::sqrt(h) < 0 || t >= best) return;
    best = t;
    best_normal = (oc + t * direction).normalized();
  };
  if (m0 <= rr * rr) {
    // One sphere holds the other: the hull is the bigger sphere.
    if (ra >= rb) sphere(oa, ra); else sphere(ob, rb);
  } else {
    // The cone's side: a quadratic in t (Quilez, "round cone" intersector).
    const double m1 = ba.dot(oa), m2 = ba.dot(direction), m3 = direction.dot(oa);
    const double m5 = oa.dot(oa);
    const double d2 = m0 - rr * rr;
    const double k2 = d2 - m2 * m2;
    const double k1 = d2 * m3 - m1 * m2 + m2 * rr * ra;
    const double k0 = d2 * m5 - m1 * m1 + 2 * m1 * rr * ra - m0 * ra * ra;
    const double h = k1 * k1 - k0 * k2;
    // h < 0: the line misses the cone's surface; the caps are still tested, which keeps
    // rays along the axis (inside the double cone throughout) right.
    if (h >= 0 && std::abs(k2) > 1e-12) {
      const double t = (-std::sqrt(h) - k1) / k2;
      const double y = m1 - ra * rr + t * m2;
      if (y > 0 && y < d2 && t >= 0) {
        best = t;
        best_normal = (d2 * (oa + t * direction) - ba * y).normalized();
      }
    }
    // The caps: whichever sphere the ray enters first, if it does so before the side.
    sphere(oa, ra);
    sphere(ob, rb);
  }
  if (!std::isfinite(best)) return false;
  *t_hit = best;
  if (normal) *normal = best_normal;
  return true;
}

cv::Mat BodyImage::Mask() const { return part != kNoPart; }

namespace {

// Whether a sphere (centre `c` from the camera centre, radius `r`) meets a tile's cone: the
// angle from the axis to the centre is at most the cone's half-angle plus the sphere's
// angular radius (every ray that enters the sphere is within that angle of it). The sphere
// is grown by a millionth so that rounding can only let more parts through.
bool SphereMeetsCone(const Eigen::Vector3d& c, double r, const Eigen::Vector3d& axis, double cos_half,
                     double sin_half) {
  const double d = c.norm();
  r = r * (1 + 1e-6) + 1e-6;
  if (d <= r || cos_half <= -1) return true;
  const double sin_b = r / d, cos_b = std::sqrt(1 - sin_b * sin_b);
  // cos and sin of (half-angle + angular radius); a sum of pi or more holds every direction.
  const double cos_sum = cos_half * cos_b - sin_half * sin_b;
  const double sin_sum = sin_half * cos_b + cos_half * sin_b;
  if (sin_sum <= 0 && cos_sum < 0) return true;
  return c.dot(axis) >= d * (cos_sum - 1e-9);
}

}  // namespace

RayCaster::RayCaster(const Camera& camera) : camera_(camera), centre_(camera.CentreInWorld()) {
  Eigen::Matrix2Xd pixels(2, static_cast<Eigen::Index>(camera.width) * camera.height);
  for (int v = 0; v < camera.height; ++v)
    for (int u = 0; u < camera.width; ++u) pixels.col(v * camera.width + u) << u, v;
  rays_ = camera.PixelRaysInWorld(pixels);
  tiles_across_ = (camera.width + kTilePx - 1) / kTilePx;
  tiles_down_ = (camera.height + kTilePx - 1) / kTilePx;
  tiles_.resize(static_cast<size_t>(tiles_across_) * tiles_down_);
  for (int ty = 0; ty < tiles_down_; ++ty)
    for (int tx = 0; tx < tiles_across_; ++tx) {
      const int u0 = tx * kTilePx, u1 = std::min(camera.width, u0 + kTilePx);
      const int v0 = ty * kTilePx, v1 = std::min(camera.height, v0 + kTilePx);
      TileCone& cone = tiles_[ty * tiles_across_ + tx];
      Eigen::Vector3d sum = Eigen::Vector3d::Zero();
      bool finite = true;
      for (int v = v0; v < v1; ++v)
        for (int u = u0; u < u1; ++u) {
          const Eigen::Vector3d ray = rays_.col(v * camera.width + u);
          finite = finite && ray.allFinite();
          sum += ray;
        }
      cone = {Eigen::Vector3d::UnitZ(), -1, 0};  // every direction
      if (!finite || sum.norm() < 1e-9) continue;
      cone.axis = sum.normalized();
      double cos_half = 1;
      for (int v = v0; v < v1; ++v)
        for (int u = u0; u < u1; ++u) cos_half = std::min(cos_half, cone.axis.dot(rays_.col(v * camera.width + u)));
      cone.cos_half = std::max(-1.0, cos_half - 1e-9);
      cone.sin_half = std::sqrt(std::max(0.0, 1 - cone.cos_half * cone.cos_half));
    }
}

void RayCaster::Render(const std::vector<Capsule>& capsules, BodyImage* image) const {
  JGPM_CHECK(capsules.size() < BodyImage::kNoPart);
  const int width = camera_.width, height = camera_.height;
  image->part.create(height, width, CV_8UC1);
  image->depth_mm.create(height, width, CV_32FC1);
  image->normal.create(height, width, CV_32FC3);
  // Bounding sphere of each capsule: most rays miss most parts with one test.
  std::vector<Eigen::Vector3d> centre(capsules.size());
  std::vector<double> radius(capsules.size());
  for (size_t i = 0; i < capsules.size(); ++i) {
    const Capsule& c = capsules[i];
    centre[i] = 0.5 * (c.from_mm + c.to_mm) - centre_;
    radius[i] = 0.5 * (c.to_mm - c.from_mm).norm() + std::max(c.radius_from_mm, c.radius_to_mm);
  }
  cv::parallel_for_(cv::Range(0, tiles_down_), [&](const cv::Range& tile_rows) {
    std::vector<int> near;  // the parts whose bounding spheres meet the tile's cone, in order
    near.reserve(capsules.size());
    for (int ty = tile_rows.start; ty < tile_rows.end; ++ty)
      for (int tx = 0; tx < tiles_across_; ++tx) {
        const TileCone& cone = tiles_[ty * tiles_across_ + tx];
        near.clear();
        for (size_t i = 0; i < capsules.size(); ++i)
          if (SphereMeetsCone(centre[i], radius[i], cone.axis, cone.cos_half, cone.sin_half))
            near.push_back(static_cast<int>(i));
        const int u0 = tx * kTilePx, u1 = std::min(width, u0 + kTilePx);
        const int v0 = ty * kTilePx, v1 = std::min(height, v0 + kTilePx);
        for (int v = v0; v < v1; ++v) {
          uint8_t* part = image->part.ptr<uint8_t>(v);
          float* depth = image->depth_mm.ptr<float>(v);
          cv::Vec3f* normal = image->normal.ptr<cv::Vec3f>(v);
          if (near.empty()) {
            std::fill(part + u0, part + u1, static_cast<uint8_t>(BodyImage::kNoPart));
            std::fill(depth + u0, depth + u1, 0.f);
            std::fill(normal + u0, normal + u1, cv::Vec3f(0, 0, 0));
            continue;
          }
          for (int u = u0; u < u1; ++u) {
            const Eigen::Vector3d ray = rays_.col(v * width + u);
            double nearest = std::numeric_limits<double>::infinity();
            int nearest_part = BodyImage::kNoPart;
            Eigen::Vector3d nearest_normal = Eigen::Vector3d::Zero();
            for (const int i : near) {
              const double along = centre[i].dot(ray);
              if (centre[i].squaredNorm() - along * along > radius[i] * radius[i]) continue;
              double t;
              Eigen::Vector3d n;
              if (IntersectCapsule(centre_, ray, capsules[i], &t, &n) && t < nearest) {
                nearest = t;
                nearest_part = i;
                nearest_normal = n;
              }
            }
            part[u] = static_cast<uint8_t>(nearest_part);
            depth[u] = nearest_part == BodyImage::kNoPart ? 0.f : static_cast<float>(nearest);
            normal[u] = cv::Vec3f(nearest_normal.x(), nearest_normal.y(), nearest_normal.z());
          }
        }
      }
  });
}

}  // namespace jgpm
