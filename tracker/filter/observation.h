// One camera's foreground mask, prepared once per frame for the likelihood: the foreground
// inside the region where the person is expected, packed for the bit silhouettes, and the
// truncated distance from every pixel near that region to the nearest foreground pixel.
//
// Only a window about the region is prepared (the region grown by the truncation and two
// pixels): the distance at any point of the region depends only on foreground within the
// truncation of it, so there it equals the whole image's distance, at a fraction of the
// cost (the distance transform and hole filling over the whole image were a millisecond a
// camera, a tenth of a frame's budget with one camera). Outside the window the distance
// is the truncation: foreground far from where the person is expected, such as clutter,
// does not pull the body's outline, as it does not count in the area term either.
#pragma once

#include <memory>
#include <vector>

#include <opencv2/core/mat.hpp>

#include "tracker/body/bit_silhouette.h"
#include "tracker/filter/occluder_layers.h"

namespace jgpm {

class CameraObservation {
 public:
  CameraObservation() = default;
  // `mask`: CV_8UC1, nonzero = foreground; `region`: where the person is expected (clipped
  // to the image). Holes of fewer than `max_hole_px` pixels enclosed by foreground inside
  // the window are filled first (a segmentation's speckle, not the gap between a limb and
  // the body). Distances are truncated at `truncation_px`. An empty mask (nobody in view)
  // is valid.
  // `hidden` (may be empty; else CV_8UC1 of the mask's size): where other people are drawn
  // (several people tracked at once): their pixels are neither foreground this person must
  // explain nor background it may not cover (behind them it could be; in front of them it
  // could cover them), so the body pays nothing there either way: they leave the mask, and
  // count as foreground for the body's outline and its pixels outside the mask.
  CameraObservation(const cv::Mat& mask, cv::Rect region, double truncation_px, int max_hole_px = 0,
                    const cv::Mat& hidden = cv::Mat());

  // The mask with the window's holes filled (and without the hidden pixels).
  const cv::Mat& mask() const { return mask_; }
  bool empty() const { return mask_.empty(); }
  // Foreground pixels in the whole image.
  int Foreground() const { return foreground_; }
  // Distance (px, at most the truncation) from (u, v) to the nearest foreground pixel; the
  // truncation outside the window or when it holds no foreground.
  float DistanceToForeground(float u, float v) const {
    u -= window_x_, v -= window_y_;
    if (!(u >= -0.5f && v >= -0.5f && u < width_ - 0.5f && v < height_ - 0.5f)) {
      return static_cast<float>(truncation_px_);
    }
    return distance_row_[static_cast<int>(v + 0.5f) * stride_ + static_cast<int>(u + 0.5f)];
  }
  double truncation_px() const { return truncation_px_; }
  // Whether (u, v) is in the image at all: beyond its edges nobody knows what is there.
  bool InImage(float u, float v) const {
    return u >= -0.5f && v >= -0.5f && u < mask_.cols - 0.5f && v < mask_.rows - 0.5f;
  }

  // The region where the person is expected: the foreground inside it, packed, and its
  // count.
  const cv::Rect& region() const { return region_; }
  const cv::Rect& window() const { return window_; }
  const BitMask& region_bits() const { return region_bits_; }
  const BitMask& region_bits_grown() const { return region_grown_; }  // grown by a pixel,
                                                                       // and the hidden pixels
  int region_count() const { return region_count_; }

  // Painted occluders in depth (tracker/filter/occluder_layers.h): `objects`, painted
  // objects near the region, and `by_subset[s]` for s < 2^objects - 1, the observation
  // made with only those of them whose bit is set in s hidden (the painting's other objects
  // hidden all the same). This one, made with all of them hidden, is the last subset.
  void SetPaintedObjects(std::vector<PaintedObject> objects, std::vector<CameraObservation> by_subset);
  bool layered() const { return painted_ != nullptr; }
  const std::vector<PaintedObject>& painted_objects() const { return painted_->objects; }
  const CameraObservation& WithHidden(unsigned subset) const {
    return subset < painted_->by_subset.size() ? painted_->by_subset[subset] : *this;
  }

 private:
  cv::Mat mask_;
  cv::Mat distance_;  // CV_32F, the window's
  const float* distance_row_ = nullptr;
  float window_x_ = 0, window_y_ = 0;
  int width_ = 0, height_ = 0, stride_ = 0;  // 0 x 0 when nothing is near: every lookup is outside
  double truncation_px_ = 0;
  int foreground_ = 0;
  cv::Rect region_, window_;
  BitMask region_bits_, region_grown_;
  int region_count_ = 0;
  struct Painted {
    std::vector<PaintedObject> objects;
    std::vector<CameraObservation> by_subset;
  };
  std::shared_ptr<const Painted> painted_;
};

}  // namespace jgpm
