#include "tracker/body/ray_caster.h"

#include <cmath>
#include <limits>

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

RayCaster::RayCaster(const Camera& camera) : camera_(camera), centre_(camera.CentreInWorld()) {
  Eigen::Matrix2Xd pixels(2, static_cast<Eigen::Index>(camera.width) * camera.height);
  for (int v = 0; v < camera.height; ++v)
    for (int u = 0; u < camera.width; ++u) pixels.col(v * camera.width + u) << u, v;
  rays_ = camera.PixelRaysInWorld(pixels);
}

void RayCaster::Render(const std::vector<Capsule>& capsules, BodyImage* image) const {
  JGPM_CHECK(capsules.size() < BodyImage::kNoPart);
  const int width = camera_.width, height = camera_.height;
  image->part.create(height, width, CV_8UC1);
  image->depth_mm.create(height, width, CV_32FC1);
  image->normal.create(height, width, CV_32FC3);
  // Bounding sphere of each capsule: most rays miss most parts with one test.
  std::vector<Eigen::Vector3d> centre(capsules.size());
  std::vector<double> radius2(capsules.size());
  for (size_t i = 0; i < capsules.size(); ++i) {
    const Capsule& c = capsules[i];
    centre[i] = 0.5 * (c.from_mm + c.to_mm) - centre_;
    const double r = 0.5 * (c.to_mm - c.from_mm).norm() + std::max(c.radius_from_mm, c.radius_to_mm);
    radius2[i] = r * r;
  }
  cv::parallel_for_(cv::Range(0, height), [&](const cv::Range& rows) {
    for (int v = rows.start; v < rows.end; ++v) {
      uint8_t* part = image->part.ptr<uint8_t>(v);
      float* depth = image->depth_mm.ptr<float>(v);
      cv::Vec3f* normal = image->normal.ptr<cv::Vec3f>(v);
      for (int u = 0; u < width; ++u) {
        const Eigen::Vector3d ray = rays_.col(v * width + u);
        double nearest = std::numeric_limits<double>::infinity();
        int nearest_part = BodyImage::kNoPart;
        Eigen::Vector3d nearest_normal = Eigen::Vector3d::Zero();
        for (size_t i = 0; i < capsules.size(); ++i) {
          const double along = centre[i].dot(ray);
          if (centre[i].squaredNorm() - along * along > radius2[i]) continue;
          double t;
          Eigen::Vector3d n;
          if (IntersectCapsule(centre_, ray, capsules[i], &t, &n) && t < nearest) {
            nearest = t;
            nearest_part = static_cast<int>(i);
            nearest_normal = n;
          }
        }
        part[u] = static_cast<uint8_t>(nearest_part);
        depth[u] = nearest_part == BodyImage::kNoPart ? 0.f : static_cast<float>(nearest);
        normal[u] = cv::Vec3f(nearest_normal.x(), nearest_normal.y(), nearest_normal.z());
      }
    }
  });
}

}  // namespace jgpm
