// Static occluders a user paints once for a fixed camera: the tables, pillars, signs and
// parked cars that stand between the camera and where people walk (255 where one is, an
// image of the camera's size). A person's mask ends where such an object begins, which a
// single camera cannot tell from their feet: on the one-camera clip behind two tables
// (realism suite, 35_12-1cam-occluders) the tracker read the tables' top edge as the feet
// and placed the walker 1.4 m too far, size 1.07, for 80 of 100 frames (1111 mm).
// Painted, those pixels are the frame's `hidden` ones (frame_source.h): the likelihood
// neither needs them explained nor forbids a body there (tracker/filter/observation.h),
// a blob resting on them has its feet hidden and is placed between the painting's lower
// edge and its own bottom, its head at an adult's height (tracker/filter/person_locator.h),
// and a start from such a blob holds its size until the feet show (tracker/filter/tracker.h):
// 1111 -> 75.7 mm on that clip (4 seeds; its clean twin 55.5). A synthetic clip's
// painting is written by `jgpm render` (occluders/CAMERA.png: each object that hid a
// walker, whole); a video's is given with `jgpm track --occluders PNG` per camera.
//
// With one person tracked, a painted object hides only a body behind it: it stands on the
// floor, and a body nearer than its nearest foot is in front (tracker/filter/
// occluder_layers.h). With several, it hides every body: a person who walks in front of
// one loses those pixels as evidence (not charged, not needed).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <opencv2/core/mat.hpp>

#include "calibration/camera.h"
#include "tracker/frames/frame_source.h"

namespace jgpm {

// The painting at `path` for `camera`: CV_8UC1, 255 where any colour channel is non-zero
// (and the alpha channel, when there is one).
// InputError naming the file: unreadable, or not of the camera's image size.
cv::Mat ReadOccluderMask(const std::string& path, const Camera& camera);

// `inner`'s frames with each camera's painting as their hidden pixels (at the size of
// that camera's masks, working_resolution.h's ScaleHidden). An empty painting leaves that
// camera without.
class OccludedSource : public FrameSource {
 public:
  OccludedSource(std::unique_ptr<FrameSource> inner, std::vector<cv::Mat> paintings);

  const std::vector<Camera>& cameras() const override { return inner_->cameras(); }
  double fps() const override { return inner_->fps(); }
  int NumFrames() const override { return inner_->NumFrames(); }
  bool Next(Frame* frame) override;
  double mask_scale(size_t camera) const override { return inner_->mask_scale(camera); }
  FrameSource* inner() const { return inner_.get(); }

 private:
  std::unique_ptr<FrameSource> inner_;
  std::vector<cv::Mat> paintings_, scaled_;  // scaled_: at the masks' size, made once
};

}  // namespace jgpm
