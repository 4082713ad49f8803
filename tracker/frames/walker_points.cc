





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
    // The centroid of the blob's pixels in rows [from, to).
    auto rows = [h](double share) { return std::max(1, static_cast<int>(std::lround(share * h))); };
    auto centroid = [&](int from, int to) {
      Eigen::Vector2d sum = Eigen::Vector2d::Zero();
      int n = 0;
      for (int r = from; r < to; ++r) {
        const int* row = labels.ptr<int>(r);
        for (int c = x; c < x + w; ++c) {
          if (row[c] == label) {
            sum += Eigen::Vector2d(c, r);
            ++n;
          }
        }
      }
      return Eigen::Vector2d(sum / n);  // the blob's top and bottom rows hold pixels of it
    };
    Blob blob;
    // The head: the top edge, not the top pixel's centre (a pixel is foreground when its
    // centre is inside the person).
    blob.point.head_px = {centroid(y, y + rows(options_.head_share)).x(), y - 0.5};
    blob.point.foot_px = centroid(y + h - rows(options_.foot_share), y + h);
    blob.point.frame = frame_;
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
      const double distance = (track.last_head - blob.point.head_px).norm();
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
    tracks_[best] = {frame_, blob.point.head_px, blob.height};
    blob.point.walker = best;
    points_.push_back(blob.point);
    heights_.push_back(blob.height);
  }
  ++frame_;
}

std::vector<HeadFoot> WalkerPointFinder::Points() const {
  // Each walker's points in time order.
  std::vector<std::vector<int>> of(tracks_.size());
  for (size_t i = 0; i < points_.size(); ++i) of[points_[i].walker].push_back(static_cast<int>(i));
  // A blob whose height strays from its neighbours' median lost or gained a part.
  std::vector<bool> keep(points_.size(), false);
  std::vector<int> seen(tracks_.size(), 0);
  const int half = options_.height_window_frames / 2;
  for (size_t t = 0; t < of.size(); ++t) {
    const std::vector<int>& own = of[t];
    for (size_t k = 0; k < own.size(); ++k) {
      std::vector<double> around;
      for (size_t j = k > size_t(half) ? k - half : 0; j < std::min(own.size(), k + half + 1); ++j) {
        around.push_back(heights_[own[j]]);
      }
      std::nth_element(around.begin(), around.begin() + around.size() / 2, around.end());
      const double median = around[around.size() / 2];
      if (std::abs(heights_[own[k]] - median) <= options_.height_tolerance * median) {
        keep[own[k]] = true;
        ++seen[t];
      }
    }
  }
  std::vector<int> number(tracks_.size(), -1);
  int walkers = 0;
  for (size_t t = 0; t < tracks_.size(); ++t) {
    if (seen[t] >= options_.min_frames) number[t] = walkers++;
  }
  std::vector<HeadFoot> kept;
  for (size_t i = 0; i < points_.size(); ++i) {
    if (!keep[i] || number[points_[i].walker] < 0) continue;
    HeadFoot point = points_[i];
    point.walker = number[point.walker];
    kept.push_back(point);
  }
  return kept;
}

}  // namespace jgpm
