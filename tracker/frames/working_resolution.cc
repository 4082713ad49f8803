#include "tracker/frames/working_resolution.h"

#include <algorithm>
#include <cmath>

#include <opencv2/imgproc.hpp>

#include "io/base/error.h"

namespace jgpm {

Camera ScaleCamera(const Camera& camera, double s) {
  Camera scaled = camera;
  scaled.width = std::max(1, static_cast<int>(std::lround(camera.width * s)));
  scaled.height = std::max(1, static_cast<int>(std::lround(camera.height * s)));
  // The scale the rounded size really has, per axis; pixel centres at integers stay so:
  // u' + 0.5 = s (u + 0.5).
  const double sx = static_cast<double>(scaled.width) / camera.width;
  const double sy = static_cast<double>(scaled.height) / camera.height;
  scaled.fx = camera.fx * sx;
  scaled.fy = camera.fy * sy;
  scaled.cx = (camera.cx + 0.5) * sx - 0.5;
  scaled.cy = (camera.cy + 0.5) * sy - 0.5;
  return scaled;
}

cv::Mat ScaleMask(const cv::Mat& mask, cv::Size size) {
  if (mask.size() == size) return mask;
  cv::Mat area;
  cv::resize(mask, area, size, 0, 0, cv::INTER_AREA);
  return area >= 128;
}

cv::Mat ScaleHidden(const cv::Mat& hidden, cv::Size size) {
  if (hidden.empty() || hidden.size() == size) return hidden;
  cv::Mat area;
  cv::resize(hidden, area, size, 0, 0, cv::INTER_AREA);
  return area > 0;
}

namespace {

// The tallest blob of a mask, px (0 when empty). Specks were removed by the source.
int TallestBlob(const cv::Mat& mask) {
  if (mask.empty()) return 0;
  cv::Mat labels, stats, centroids;
  const int count = cv::connectedComponentsWithStats(mask, labels, stats, centroids, 8, CV_32S);
  int tallest = 0;
  for (int k = 1; k < count; ++k) tallest = std::max(tallest, stats.at<int>(k, cv::CC_STAT_HEIGHT));
  return tallest;
}

}  // namespace

WorkingResolutionSource::WorkingResolutionSource(std::unique_ptr<FrameSource> inner,
                                                 const WorkingResolutionOptions& options, bool live)
    : inner_(std::move(inner)) {
  JGPM_CHECK(inner_);
  const std::vector<Camera>& cameras = inner_->cameras();
  std::vector<int> tallest(cameras.size(), 0);
  if (options.enabled && !live) {
    Frame frame;
    while (static_cast<int>(ahead_.size()) < options.lookahead_frames && inner_->Next(&frame)) {
      for (size_t c = 0; c < cameras.size() && c < frame.masks.size(); ++c) {
        tallest[c] = std::max(tallest[c], TallestBlob(frame.masks[c]));
      }
      ahead_.push_back(frame);
    }
  }
  for (size_t c = 0; c < cameras.size(); ++c) {
    // Masks already made at a working size are kept at it (measured in them, the people
    // would be about person_px tall: no second resampling).
    const double made = inner_->mask_scale(c);
    const double s = made < 1 ? made : tallest[c] > options.person_px ? options.person_px / tallest[c] : 1.0;
    scales_.push_back(s);
    scaled_.push_back(s < 1 ? ScaleCamera(cameras[c], s) : cameras[c]);
  }
}

void WorkingResolutionSource::Scale(Frame* frame) const {
  for (size_t c = 0; c < frame->masks.size() && c < scaled_.size(); ++c) {
    if (!frame->masks[c].empty()) {
      frame->masks[c] = ScaleMask(frame->masks[c], cv::Size(scaled_[c].width, scaled_[c].height));
    }
    if (c < frame->hidden.size()) {
      frame->hidden[c] = ScaleHidden(frame->hidden[c], cv::Size(scaled_[c].width, scaled_[c].height));
    }
  }
}

bool WorkingResolutionSource::Next(Frame* frame) {
  if (!ahead_.empty()) {
    *frame = std::move(ahead_.front());
    ahead_.pop_front();
  } else if (!inner_->Next(frame)) {
    return false;
  }
  Scale(frame);
  return true;
}

}  // namespace jgpm
