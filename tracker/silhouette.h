// Fast silhouette rendering for the particle filter: the body's binary mask as a camera
// sees it. Each capsule is drawn as the convex hull of its two end spheres' images, each
// sphere imaged as a circle of radius f r / z around its projected centre (through the lens
// distortion), filled with OpenCV's sub-pixel convex-polygon fill. That approximates the
// exact image (an ellipse per sphere, distortion across the radius): the ray caster
// (tracker/ray_caster.h) is exact and the tests bound the difference.
#pragma once

#include <vector>

#include <opencv2/core/mat.hpp>

#include "calibration/camera.h"
#include "tracker/body_model.h"

namespace jgpm {

class SilhouetteRenderer {
 public:
  // Copies the camera.
  explicit SilhouetteRenderer(const Camera& camera);

  const Camera& camera() const { return camera_; }
  // Clears `mask` to 0 (allocating it as CV_8U of the camera's size when needed) and sets
  // the pixels inside the union of the capsules to 255. A capsule with an end closer than
  // 100 mm to the camera plane (or behind it) is skipped. Returns the bounding box of what
  // was drawn (empty when nothing was).
  cv::Rect Render(const std::vector<Capsule>& capsules, cv::Mat* mask) const;

 private:
  Camera camera_;
  double focal_px_;  // mean of fx and fy: circles assume square pixels
};

}  // namespace jgpm
