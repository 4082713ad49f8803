#include "tracker/filter/observation.h"

#include <cmath>
#include <vector>

#include <opencv2/imgproc.hpp>

namespace jgpm {

CameraObservation::CameraObservation(const cv::Mat& mask, cv::Rect region, double truncation_px, int max_hole_px,
                                     const cv::Mat& hidden)
    : mask_(mask), truncation_px_(truncation_px) {
  if (mask_.empty()) return;
  if (!hidden.empty()) {
    CV_Assert(hidden.size() == mask_.size() && hidden.type() == CV_8UC1);
    mask_ = mask_.clone();  // the caller's frame stays as it was
    mask_.setTo(0, hidden);
  }
  const cv::Rect image(0, 0, mask_.cols, mask_.rows);
  region_ = region & image;
  foreground_ = cv::countNonZero(mask_);
  if (region_.empty()) {
    // Nowhere to look in this image: blank packed masks of its size (a body drawn here
    // explains nothing, and is counted against nothing).
    region_bits_ = BitMask(mask_.cols, mask_.rows);
    region_grown_ = BitMask(mask_.cols, mask_.rows);
    return;
  }
  const int pad = static_cast<int>(std::ceil(truncation_px)) + 2;
  window_ = cv::Rect(region_.x - pad, region_.y - pad, region_.width + 2 * pad, region_.height + 2 * pad) & image;
  if (max_hole_px > 0) {
    // Background components that do not touch the window's border and are small are holes.
    cv::Mat labels, stats, centroids;
    const int n = cv::connectedComponentsWithStats(mask_(window_) == 0, labels, stats, centroids, 4, CV_32S);
    std::vector<uint8_t> fill(n, 0);
    bool any = false;
    for (int l = 1; l < n; ++l) {
      const int x = stats.at<int>(l, cv::CC_STAT_LEFT), y = stats.at<int>(l, cv::CC_STAT_TOP);
      const int w = stats.at<int>(l, cv::CC_STAT_WIDTH), h = stats.at<int>(l, cv::CC_STAT_HEIGHT);
      const bool border = x == 0 || y == 0 || x + w == window_.width || y + h == window_.height;
      if (!border && stats.at<int>(l, cv::CC_STAT_AREA) < max_hole_px) fill[l] = 1, any = true;
    }
    if (any) {
      mask_ = mask_.clone();  // the caller's frame stays as it was
      cv::Mat filled = mask_(window_);
      for (int v = 0; v < filled.rows; ++v) {
        const int* label = labels.ptr<int>(v);
        uint8_t* out = filled.ptr<uint8_t>(v);
        for (int u = 0; u < filled.cols; ++u)
          if (fill[label[u]]) out[u] = 255;
      }
    }
  }
  if (!hidden.empty()) mask_.setTo(0, hidden);  // a hole filled over someone else is theirs
  region_bits_ = BitMask::FromMat(mask_, region_);
  region_bits_.DilateInto(&region_grown_);
  region_count_ = region_bits_.Count();
  cv::Mat background = mask_(window_) == 0;
  if (!hidden.empty()) {
    region_grown_.Or(BitMask::FromMat(hidden, image));
    background.setTo(0, hidden(window_));
  }
  if (cv::countNonZero(background) == background.total()) return;  // no foreground near
  // distanceTransform measures to the nearest zero pixel: zeros where the foreground is.
  cv::distanceTransform(background, distance_, cv::DIST_L2, cv::DIST_MASK_PRECISE);
  // Distances are to pixel centres: a point on the foreground's edge is half a pixel (a
  // diagonal one 0.7) from the nearest, and costs nothing.
  distance_ -= 0.75;
  cv::max(distance_, 0.0, distance_);
  cv::min(distance_, truncation_px, distance_);
  distance_row_ = distance_.ptr<float>(0);
  stride_ = static_cast<int>(distance_.step1());
  window_x_ = static_cast<float>(window_.x), window_y_ = static_cast<float>(window_.y);
  width_ = window_.width, height_ = window_.height;
}

void CameraObservation::SetPaintedObjects(std::vector<PaintedObject> objects,
                                          std::vector<CameraObservation> by_subset) {
  CV_Assert(objects.size() < 8 && by_subset.size() + 1 == (1u << objects.size()));
  painted_ = std::make_shared<const Painted>(Painted{std::move(objects), std::move(by_subset)});
}

}  // namespace jgpm
