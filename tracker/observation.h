// One camera's foreground mask, prepared once per frame for the likelihood: the mask, the
// truncated distance from every pixel to the nearest foreground pixel (0 on it), an
// integral image for counting foreground in any rectangle, and the foreground inside the
// region where the person is expected, packed for the bit silhouettes.
#pragma once

#include <opencv2/core/mat.hpp>

#include "tracker/bit_silhouette.h"

namespace jgpm {

class CameraObservation {
 public:
  CameraObservation() = default;
  // `mask`: CV_8UC1, nonzero = foreground. Holes of fewer than `max_hole_px` pixels
  // enclosed by foreground are filled first (a segmentation's speckle, not the gap between
  // a limb and the body). Distances are truncated at `truncation_px`. An empty mask (nobody
  // in view) is valid.
  CameraObservation(const cv::Mat& mask, double truncation_px, int max_hole_px = 0);

  const cv::Mat& mask() const { return mask_; }
  bool empty() const { return mask_.empty(); }
  int width() const { return mask_.cols; }
  int height() const { return mask_.rows; }
  // Foreground pixels in `box` (clipped to the image).
  int ForegroundIn(cv::Rect box) const;
  int Foreground() const { return ForegroundIn(cv::Rect(0, 0, mask_.cols, mask_.rows)); }
  // Distance (px, at most the truncation) from (u, v) to the nearest foreground pixel; the
  // truncation outside the image or when there is no foreground.
  float DistanceToForeground(float u, float v) const;
  double truncation_px() const { return truncation_px_; }

  // The region where the person is expected: the foreground inside it, packed, and its
  // count. Until set, the region is empty.
  void SetRegion(cv::Rect region);
  const cv::Rect& region() const { return region_; }
  const BitMask& region_bits() const { return region_bits_; }
  const BitMask& region_bits_grown() const { return region_grown_; }  // grown by a pixel
  int region_count() const { return region_count_; }

 private:
  cv::Mat mask_;
  cv::Mat distance_;  // CV_32F
  const float* distance_row_ = nullptr;
  int width_ = 0, height_ = 0, stride_ = 0;  // 0 x 0 when empty: every lookup is outside
  cv::Mat integral_;  // CV_32S, (rows + 1) x (cols + 1)
  double truncation_px_ = 0;
  cv::Rect region_;
  BitMask region_bits_, region_grown_;
  int region_count_ = 0;
};

}  // namespace jgpm
