// Exact rendering of the body: one ray per pixel centre, through the camera's full lens
// model, intersected analytically with every tapered capsule (the convex hull of its two
// end spheres; Quilez's round-cone intersection). It gives the ground-truth masks of the
// synthetic clips, their shading (depth order, surface normals), and the oracle the fast
// SilhouetteRenderer is tested against. Milliseconds per image, not microseconds.
//
// Why tiles: a walker covers a few percent of a surveillance or webcam image, yet testing
// every pixel's ray against every part's bounding sphere was 90% of `jgpm render`'s time
// (and of the sanitizer build's, where Eigen's 3-vector operations are not inlined). Each
// 16x16 tile of pixels keeps the cone that holds its rays; a part is tried on a tile's
// pixels only if its bounding sphere meets that cone. The test is conservative, so the
// images are the same as testing every pixel (ray_caster_test checks this).
#pragma once

#include <vector>

#include <Eigen/Core>
#include <opencv2/core/mat.hpp>

#include "calibration/camera.h"
#include "tracker/body/body_model.h"

namespace jgpm {

// Where the unit ray origin + t direction first enters the capsule (t >= 0), with the
// outward surface normal there; false when it misses. A ray starting inside reports t=0.
bool IntersectCapsule(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction,
                      const Capsule& capsule, double* t, Eigen::Vector3d* normal);

// What each pixel sees of the body.
struct BodyImage {
  cv::Mat part;       // CV_8U: index of the nearest capsule hit, kNoPart where none
  cv::Mat depth_mm;   // CV_32F: distance along the ray to it (0 where none)
  cv::Mat normal;     // CV_32FC3: its outward unit normal, world frame (x, y, z)
  static constexpr int kNoPart = 255;
  cv::Mat Mask() const;  // CV_8U: 255 where part != kNoPart
};

class RayCaster {
 public:
  // Copies the camera and undistorts every pixel centre once (W x H rays).
  explicit RayCaster(const Camera& camera);

  const Camera& camera() const { return camera_; }
  const Eigen::Vector3d& centre_in_world_mm() const { return centre_; }
  // World-frame unit ray through pixel (u, v): column v * width + u.
  const Eigen::Matrix3Xd& rays() const { return rays_; }
  // At most kNoPart capsules (parallel over rows of tiles with OpenCV's thread pool).
  void Render(const std::vector<Capsule>& capsules, BodyImage* image) const;

  static constexpr int kTilePx = 16;

 private:
  // The cone from the camera centre about `axis` (unit) with half-angle acos(cos_half)
  // that holds every ray of a tile; cos_half = -1 (the whole sphere) when a ray is not
  // finite.
  struct TileCone {
    Eigen::Vector3d axis;
    double cos_half, sin_half;
  };
  Camera camera_;
  Eigen::Vector3d centre_;
  Eigen::Matrix3Xd rays_;
  int tiles_across_ = 0, tiles_down_ = 0;
  std::vector<TileCone> tiles_;  // row-major
};

}  // namespace jgpm
