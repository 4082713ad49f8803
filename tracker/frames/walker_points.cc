#include "tracker/frames/walker_points.h"

#include <algorithm>
#include <cmath>

#include <opencv2/imgproc.hpp>

#include "io/base/error.h"

namespace jgpm {

WalkerPointFinder::WalkerPointFinder(int width, int height, const WalkerPointOptions& options)
    : options_(options), width_(width), height_(height) {
  JGPM_CHECK(width > 0 && height > 0);
}

void WalkerPointFinder::Add(const cv::Mat& mask) {
  JGPM_CHECK(mask.type() == CV_8UC1 && mask.cols == width_ && mask.rows == height_);
  cv::Mat labels, stats, centroids;
  const int count = cv::connectedComponentsWithStats(mask, labels, stats, centroids, 8, CV_32S);
  struct Blob {
    HeadFoot point;
    double height;
  };
  std::vector<Blob> blobs;
  for (int label = 1; label < count; ++label) {
    const int x = stats.at<int>(label, cv::CC_STAT_LEFT), y = stats.at<int>(label, cv::CC_STAT_TOP);
    const int w = stats.at<int>(label, cv::CC_STAT_WIDTH), h = stats.at<int>(label, cv::CC_STAT_HEIGHT);
    if (h < options_.min_height * height_ || h < options_.min_aspect * w) continue;
    const int m = options_.margin_px;
    if (x < m || y < m || x + w > width_ - m || y + h > height_ - m) continue;
    // The middle column of the top and bottom rows.
    const int rows = std::max(1, static_cast<int>(std::lround(options_.end_share * h)));
    auto middle = [&](int from, int to) {
      double sum = 0;
      int n = 0;
      for (int r = from; r < to; ++r) {
        const int* row = labels.ptr<int>(r);
        for (int c = x; c < x + w; ++c) {
          if (row[c] == label) {
            sum += c;
            ++n;
          }
        }
      }
      return sum / n;  // the blob's top and bottom rows hold pixels of it by construction
    };
    Blob blob;
    // Edges, not pixel centres: a pixel is foreground when its centre is inside the person.
    blob.point.head_px = {middle(y, y + rows), y - 0.5};
    blob.point.foot_px = {middle(y + h - rows, y + h), y + h - 0.5};
    blob.height = h;
    blobs.push_back(blob);
  }
  // Larger walkers first claim their nearest track.
  std::sort(blobs.begin(), blobs.end(), [](const Blob& a, const Blob& b) { return a.height > b.height; });
  std::vector<bool> claimed(tracks_.size(), false);
  for (Blob& blob : blobs) {
    int best = -1;
    double best_distance = options_.link * blob.height;
    for (size_t t = 0; t < tracks_.size(); ++t) {
      const Track& track = tracks_[t];
      if (claimed[t] || frame_ - track.last_frame > options_.max_gap_frames) continue;
      const double distance = (track.last_foot - blob.point.foot_px).norm();
      if (distance <= best_distance) {
        best_distance = distance;
        best = static_cast<int>(t);
      }
    }
    if (best < 0) {
      best = static_cast<int>(tracks_.size());
      tracks_.push_back({});
      claimed.push_back(false);
    }
    claimed[best] = true;
    tracks_[best] = {frame_, blob.point.foot_px, blob.height};
    blob.point.walker = best;
    points_.push_back(blob.point);
  }
  ++frame_;
}

std::vector<HeadFoot> WalkerPointFinder::Points() const {
  std::vector<int> seen(tracks_.size(), 0), number(tracks_.size(), -1);
  for (const HeadFoot& point : points_) ++seen[point.walker];
  int walkers = 0;
  for (size_t t = 0; t < tracks_.size(); ++t) {
    if (seen[t] >= options_.min_frames) number[t] = walkers++;
  }
  std::vector<HeadFoot> kept;
  for (HeadFoot point : points_) {
    if (number[point.walker] < 0) continue;
    point.walker = number[point.walker];
    kept.push_back(point);
  }
  return kept;
}

}  // namespace jgpm
