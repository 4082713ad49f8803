#include "tracker/observation.h"

#include <vector>

#include <opencv2/imgproc.hpp>

namespace jgpm {

CameraObservation::CameraObservation(const cv::Mat& mask, double truncation_px, int max_hole_px)
    : mask_(mask), truncation_px_(truncation_px) {
  if (mask_.empty()) return;
  if (max_hole_px > 0) {
    // Background components that do not touch the border and are small are holes.
    cv::Mat labels, stats, centroids;
    const int n = cv::connectedComponentsWithStats(mask_ == 0, labels, stats, centroids, 4, CV_32S);
    std::vector<uint8_t> fill(n, 0);
    bool any = false;
    for (int l = 1; l < n; ++l) {
      const int x = stats.at<int>(l, cv::CC_STAT_LEFT), y = stats.at<int>(l, cv::CC_STAT_TOP);
      const int w = stats.at<int>(l, cv::CC_STAT_WIDTH), h = stats.at<int>(l, cv::CC_STAT_HEIGHT);
      const bool border = x == 0 || y == 0 || x + w == mask_.cols || y + h == mask_.rows;
      if (!border && stats.at<int>(l, cv::CC_STAT_AREA) < max_hole_px) fill[l] = 1, any = true;
    }
    if (any) {
      cv::Mat filled = mask_.clone();
      for (int v = 0; v < filled.rows; ++v) {
        const int* label = labels.ptr<int>(v);
        uint8_t* out = filled.ptr<uint8_t>(v);
        for (int u = 0; u < filled.cols; ++u)
          if (fill[label[u]]) out[u] = 255;
      }
      mask_ = filled;
    }
  }
  width_ = mask_.cols;
  height_ = mask_.rows;
  cv::Mat binary = mask_ != 0;
  cv::integral(binary / 255, integral_, CV_32S);
  if (cv::countNonZero(binary) == 0) {
    distance_ = cv::Mat(mask_.size(), CV_32F, cv::Scalar(truncation_px));
    distance_row_ = distance_.ptr<float>(0);
    stride_ = static_cast<int>(distance_.step1());
    return;
  }
  // distanceTransform measures to the nearest zero pixel: zeros where the foreground is.
  cv::Mat background = binary == 0;
  cv::distanceTransform(background, distance_, cv::DIST_L2, cv::DIST_MASK_PRECISE);
  // Distances are to pixel centres: a point on the foreground's edge is half a pixel (a
  // diagonal one 0.7) from the nearest, and costs nothing.
  distance_ -= 0.75;
  cv::max(distance_, 0.0, distance_);
  cv::min(distance_, truncation_px, distance_);
  distance_row_ = distance_.ptr<float>(0);
  stride_ = static_cast<int>(distance_.step1());
}

void CameraObservation::SetRegion(cv::Rect region) {
  region_ = mask_.empty() ? cv::Rect() : region & cv::Rect(0, 0, mask_.cols, mask_.rows);
  if (mask_.empty()) return;
  region_bits_ = BitMask::FromMat(mask_, region_);
  region_bits_.DilateInto(&region_grown_);
  region_count_ = ForegroundIn(region_);
}

int CameraObservation::ForegroundIn(cv::Rect box) const {
  if (mask_.empty()) return 0;
  box &= cv::Rect(0, 0, mask_.cols, mask_.rows);
  if (box.empty()) return 0;
  return integral_.at<int>(box.y + box.height, box.x + box.width) - integral_.at<int>(box.y, box.x + box.width) -
         integral_.at<int>(box.y + box.height, box.x) + integral_.at<int>(box.y, box.x);
}

float CameraObservation::DistanceToForeground(float u, float v) const {
  if (!(u >= -0.5f && v >= -0.5f && u < width_ - 0.5f && v < height_ - 0.5f)) return static_cast<float>(truncation_px_);
  return distance_row_[static_cast<int>(v + 0.5f) * stride_ + static_cast<int>(u + 0.5f)];
}

}  // namespace jgpm
