// Each camera's residual misalignment, learnt from the person walking by. A real
// calibration is off by a little (clip_rig.h's Miscalibrate: 0.7 degrees, 4 px of
// principal point), and at a surveillance camera's 10-20 m a 0.7-degree turn moves a
// person 120-240 mm in its image: two such views cannot both fit one body, and the pose
// bends to split the difference. Almost all of that error is, in the image, a shift, so
// each camera keeps a 2-D offset: after every tracked frame the estimate's silhouette is
// compared with the mask shifted by up to search_px pixels each way. Part of the cameras'
// best shifts is what moving the person along the floor would do, and that part is not
// the cameras' (the person's place is the tracker's to find): the floor move that best
// explains every camera's shift (least squares through each camera's image Jacobian at
// the person) is taken out, and each offset moves by `rate` of what is left. The
// likelihood then sees each mask shifted back by its offset.
//
// Bounds (the rule): an offset never exceeds twice what a real calibration's error can
// cause, 2 x (f tan 0.7 degrees + 4 px) = 0.0244 f + 8 px. With one camera an offset and
// the person's place are the same thing (nothing to align with), so a lone camera keeps
// none. The search's step (1 px) and rate (0.1, about ten frames to follow a steady
// shift) were chosen on the realism tuning clips (datasets_scripts/realism_tuning.txt).
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core/mat.hpp>

#include "calibration/camera.h"

namespace jgpm {

struct ViewAlignmentOptions {
  bool enabled = true;
  int search_px = 3;   // shifts tried each way after a frame
  double rate = 0.1;   // of the best shift taken into the offset per frame

  bool Check(std::string* why) const;
};

class ViewAlignment {
 public:
  ViewAlignment(const std::vector<Camera>& cameras, const ViewAlignmentOptions& options);

  // Pixels by which camera `c` sees the world displaced from its calibration.
  const cv::Point2d& offset(int c) const { return offsets_[c]; }
  double limit_px(int c) const { return limits_[c]; }
  bool active() const { return active_; }

  // `mask` as camera `c`'s calibrated projection would have it: moved back by the offset
  // (whole pixels; uncovered border pixels are background). The mask itself when the
  // offset rounds to zero.
  cv::Mat Apply(int c, const cv::Mat& mask) const;
  // After a frame: per camera the estimate's silhouette (CV_8U, its image size; empty: the
  // camera has no say), the mask as Apply gave it and the region compared in; `person_mm`
  // the estimate's root. Moves the offsets by what of the cameras' best shifts no move of
  // the person along the floor explains, within the limits.
  void Update(const std::vector<cv::Mat>& silhouettes, const std::vector<cv::Mat>& aligned_masks,
              const std::vector<cv::Rect>& regions, const Eigen::Vector3d& person_mm);
  // Best whole-pixel shift (dx, dy) of `mask` onto `silhouette` within `region`, each in
  // [-search, search]: exposed for tests.
  static cv::Point BestShift(const cv::Mat& silhouette, const cv::Mat& mask, const cv::Rect& region, int search);

 private:
  std::vector<Camera> cameras_;
  ViewAlignmentOptions options_;
  std::vector<cv::Point2d> offsets_;
  std::vector<double> limits_;
  bool active_ = false;
};

}  // namespace jgpm
