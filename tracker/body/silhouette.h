// Fast silhouette rendering for the particle filter: the body's binary mask as a camera
// sees it. Each capsule is drawn as the convex hull of its two end spheres' images, filled
// with OpenCV's sub-pixel convex-polygon fill. A sphere seen theta off the optical axis
// images as an ellipse whose minor semi-axis is f r / z and whose major one, along the
// line from the principal point, is 1 / cos(theta) times longer (to first order in r / z:
// 15% at 30 degrees, 41% at 45, which a wide webcam sees). Both ends of a capsule are
// stretched by the factor and along the direction of the capsule's middle, so the hull of
// the two ellipses is the affine image of the hull of two circles, drawn as such. Left out:
// the two ends' slightly different stretches, the ellipse centre's second-order shift
// outwards (f tan(theta) (r / z)^2, under 2 px for a 0.1 m part 2 m away at 40 degrees),
// and distortion across the radius. The ray caster (tracker/body/ray_caster.h) is exact and
// the tests bound the difference.
//
// Particles wander: a part may be far off the image or outside the region where the lens
// model is valid. OpenCV's distortion polynomial bends back beyond its monotone range
// (a limb far off axis would be drawn inside the image), so a part with an end outside
// that range, or further than kMaxOffImage image sizes outside the image, or closer than
// 100 mm to the camera plane, is not drawn; every coordinate cast to int is in range.
#pragma once

#include <vector>

#include <Eigen/Core>

#include <opencv2/core/mat.hpp>

#include "calibration/camera.h"
#include "tracker/body/body_model.h"

namespace jgpm {

// A capsule as a camera sees it: its end spheres' image centres (pixels, through the lens)
// and minor semi-axes f r / z (pixels); both ellipses are `stretch` = sqrt(1 + |lean|^2)
// times longer along `lean`, the capsule's middle in normalised coordinates (x/z, y/z).
// Round() maps the image to the frame where they are circles of radii ra and rb (squeezed
// along `lean` about the capsule's middle): p - (lean . (p - middle)) lean / (k (k + 1)),
// k the stretch; Image() maps back: p + (lean . (p - middle)) lean / (k + 1). (The image
// of lean lean' / |lean|^2 scaled by k - 1 = |lean|^2 / (k + 1), with no division by a
// small |lean|.)
struct ImageCapsule {
  Eigen::Vector2d a, b;
  double ra = 0, rb = 0;
  double stretch = 1;
  Eigen::Vector2d lean = Eigen::Vector2d::Zero();
  Eigen::Vector2d middle = Eigen::Vector2d::Zero();  // (a + b) / 2
  double grow = 0.5, shrink = 0.5;                  // 1 / (k + 1) and 1 / (k (k + 1))

  Eigen::Vector2d Round(const Eigen::Vector2d& p) const { return p - (shrink * lean.dot(p - middle)) * lean; }
  Eigen::Vector2d Image(const Eigen::Vector2d& p) const { return p + (grow * lean.dot(p - middle)) * lean; }
};

// Projects capsules with the culling described above; shared by the renderers.
class CapsuleProjector {
 public:
  explicit CapsuleProjector(const Camera& camera);
  const Camera& camera() const { return camera_; }
  // False when the capsule is not drawn (too near, behind, outside the lens's monotone
  // range or far off the image).
  bool Project(const Capsule& capsule, ImageCapsule* image) const;
  // Largest normalised radius sqrt(x^2 + y^2) (x = X/Z, y = Y/Z) up to which the camera's
  // radial distortion is monotone, so pixels there are the true images of the points.
  double max_normalised_radius() const { return max_radius_; }

 private:
  Camera camera_;
  double focal_px_;  // mean of fx and fy: circles assume square pixels
  double max_radius_;
};

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
  // The particle filter's form: draws into `mask` (CV_8U of the camera's size, which the
  // caller keeps zero outside what it draws) without clearing it, and appends to `outline`
  // (may be null) points along each drawn part's outline, at most `outline_step_px` apart.
  // Returns the bounding box drawn (clipped to the image).
  cv::Rect Draw(const std::vector<Capsule>& capsules, cv::Mat* mask, std::vector<Eigen::Vector2f>* outline = nullptr,
                double outline_step_px = 3) const;

  double max_normalised_radius() const { return projector_.max_normalised_radius(); }

 private:
  Camera camera_;
  CapsuleProjector projector_;
};

}  // namespace jgpm
