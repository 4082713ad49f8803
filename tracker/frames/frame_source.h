// Where the tracker's frames come from: one interface for a synthetic clip folder
// (tracker/frames/clip_source.h) and for video files, image folders and live V4L2 cameras
// (tracker/frames/video_frame_source.h); tracker/frames/frame_source_factory.h makes the one asked for.
// A source knows its cameras and hands out frames in time order; each frame carries every
// camera's foreground mask, and the colour image when the source has one (for overlays
// and background subtraction).
#pragma once

#include <algorithm>
#include <chrono>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "calibration/camera.h"

namespace jgpm {

// One moment seen by every camera of a source.
struct Frame {
  int index = 0;         // frame number in the source, from 0
  double time_s = 0;     // since the source's first frame
  bool dropped = false;  // nothing was captured: masks and images are empty
  double latency_ms = 0;  // live: from capture until the masks were ready...
  std::chrono::steady_clock::time_point ready;  // ...which was then
  std::vector<cv::Mat> masks;   // per camera: CV_8UC1, 255 = foreground
  std::vector<cv::Mat> images;  // per camera: BGR, or empty when the source has none
  // Per camera, or none: CV_8UC1, 255 where the person may be hidden: static occluders
  // the user painted (occluder_masks.h) and, several people at once, where other people
  // being tracked are drawn. Pixels this person's likelihood neither needs explained nor
  // forbids (tracker/filter/observation.h). Sources leave it empty.
  std::vector<cv::Mat> hidden;
  // Per camera, or none: the painted static occluders kept apart from `hidden`, which then
  // holds only the other people's drawings (several people at once): a painted object
  // stands somewhere and hides only who is behind it (tracker/filter/occluder_layers.h),
  // so it must not be mixed with a drawing that hides whatever is under it. Hidden pixels
  // are those of either (HiddenPixels).
  std::vector<cv::Mat> painted;
};

// Pixels hidden by either mask: their union, or the one given when the other is empty or
// of another size (not the same camera's).
inline cv::Mat EitherHidden(const cv::Mat& a, const cv::Mat& b) {
  if (a.empty() || b.empty() || a.size() != b.size()) return a.empty() ? b : a;
  return a | b;
}

// Whether at least half of a drawing (CV_8UC1) is under `cover` (empty, or of another
// size: nothing covers it).
inline bool HalfUnder(const cv::Mat& drawn, const cv::Mat& cover) {
  if (drawn.empty() || cover.size() != drawn.size()) return false;
  const int own = cv::countNonZero(drawn);
  return own > 0 && 2 * cv::countNonZero(drawn & cover) >= own;
}

// Every pixel that may hide a person in `frame`, per camera: Frame::hidden and
// Frame::painted.
inline std::vector<cv::Mat> HiddenPixels(const Frame& frame) {
  if (frame.painted.empty()) return frame.hidden;
  std::vector<cv::Mat> all(std::max(frame.hidden.size(), frame.painted.size()));
  for (size_t c = 0; c < all.size(); ++c)
    all[c] = EitherHidden(c < frame.hidden.size() ? frame.hidden[c] : cv::Mat(),
                          c < frame.painted.size() ? frame.painted[c] : cv::Mat());
  return all;
}

class FrameSource {
 public:
  virtual ~FrameSource() = default;
  virtual const std::vector<Camera>& cameras() const = 0;
  virtual double fps() const = 0;
  // Frames in the source, dropped ones included; -1 when unknown (live sources).
  virtual int NumFrames() const = 0;
  // The next frame (masks and, when `with_images` was asked of the source, images); false
  // at the end. InputError naming the file or device when a frame cannot be read.
  virtual bool Next(Frame* frame) = 0;
  // The scale of camera c's masks against its camera's image (the images stay full size):
  // below 1 when the source already made them at a working resolution.
  virtual double mask_scale(size_t /*camera*/) const { return 1; }
};

}  // namespace jgpm
