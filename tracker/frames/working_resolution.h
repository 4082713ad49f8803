// The tracker's working resolution: masks brought down to where the person is about as
// many pixels tall as the tracker's pixel constants were chosen for, whatever the input's
// size.
//
// The likelihood's and the start's constants are in pixels (outline truncation 10 px,
// outline step 3 px, minimum foreground 150 px, holes 60 px, region growth 8 px; see
// tracker/filter/likelihood.h and observation.h), chosen on clips whose walkers are 80-150
// px tall. A person 300-900 px tall (a webcam at 1280x720, a phone in portrait) makes the
// outline's basin a small share of the body and each particle's cost grow with the pixel
// count. So each camera's masks are scaled by
//   s = min(1, person_px / tallest)
// where `tallest` is the tallest foreground blob the camera shows over the first
// lookahead frames (blobs of people farther than that later get smaller, which the
// constants handle; nearer ones are bounded by the image). The camera the tracker sees is
// scaled with them (focal lengths and principal point; pixel centres stay pixel centres),
// so nothing else changes: the estimate is in the world, and overlays are drawn at full
// size through the full-size cameras. Live sources are not read ahead (a second's delay
// at the start) and keep s = 1.
#pragma once

#include <deque>
#include <memory>
#include <vector>

#include <opencv2/core/mat.hpp>

#include "calibration/camera.h"
#include "tracker/frames/frame_source.h"

namespace jgpm {

struct WorkingResolutionOptions {
  // The person's height the masks are brought to (no larger): the top of the range the
  // pixel constants were chosen on (the suite's walkers, 80-150 px), with room to spare.
  double person_px = 200;
  int lookahead_frames = 30;  // frames read ahead to see the person (1 s at 30 fps)
  bool enabled = true;
};

// The camera as seen in an image scaled by s.
Camera ScaleCamera(const Camera& camera, double s);

// A binary mask (0 / 255) brought to `size` by pixel area, a pixel on when at least half
// of it was.
cv::Mat ScaleMask(const cv::Mat& mask, cv::Size size);
// A hidden mask (frame_source.h) brought to `size`: a pixel is hidden when any of it was
// (an occluder's edge kept, not halved away).
cv::Mat ScaleHidden(const cv::Mat& hidden, cv::Size size);

class WorkingResolutionSource : public FrameSource {
 public:
  // Reads ahead (unless live) to choose each camera's scale.
  WorkingResolutionSource(std::unique_ptr<FrameSource> inner, const WorkingResolutionOptions& options, bool live);

  const std::vector<Camera>& cameras() const override { return scaled_; }  // what the tracker sees
  const std::vector<Camera>& full_cameras() const { return inner_->cameras(); }
  const std::vector<double>& scales() const { return scales_; }
  double fps() const override { return inner_->fps(); }
  int NumFrames() const override { return inner_->NumFrames(); }
  // The next frame: masks at the working resolution, images as they came.
  bool Next(Frame* frame) override;

 private:
  void Scale(Frame* frame) const;

  std::unique_ptr<FrameSource> inner_;
  std::vector<double> scales_;
  std::vector<Camera> scaled_;
  std::deque<Frame> ahead_;
};

}  // namespace jgpm
