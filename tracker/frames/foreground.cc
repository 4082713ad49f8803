#include "tracker/frames/foreground.h"

#include <algorithm>
#include <cmath>

#include <opencv2/core/utility.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/photo.hpp>

#include "io/base/error.h"

namespace jgpm {

bool ForegroundOptions::Check(std::string* why) const {
  auto fail = [why](const char* what) { return *why = what, false; };
  if (learning_frames < 1 || learning_frames > 10000) return fail("learning frames must be 1-10000");
  if (!(learning_rate >= 0 && learning_rate <= 1)) return fail("the learning rate must be in [0, 1]");
  if (!(threshold > 0 && std::isfinite(threshold))) return fail("the threshold must be positive");
  if (!(open_px >= 0 && close_px >= 0 && open_px < 50 && close_px < 50)) return fail("clean-up radii must be 0-50 px");
  if (!(min_area >= 0 && min_area < 1)) return fail("the speck size must be a fraction of the image in [0, 1)");
  return true;
}

ForegroundExtractor::ForegroundExtractor(const ForegroundOptions& options, int width, int height)
    : options_(options), width_(width), height_(height) {
  std::string why;
  if (!options.Check(&why)) ThrowInputError("foreground options", why);
}

std::vector<cv::Mat> MovingRegions(const std::vector<cv::Mat>& images, double min_area, bool tight) {
  const int n = static_cast<int>(images.size());
  std::vector<cv::Mat> grey(n), moving(n);
  if (n < 2) {
    moving.assign(n, cv::Mat::zeros(images[0].size(), CV_8UC1));
    return moving;
  }
  // Found at no more than kMaxRows rows (the largest the rule was tuned at, vtest.avi's
  // 576): the regions are coarse (joined and grown by 2% of the height), and at 1280 rows
  // the joining alone, an ellipse 51 px across, cost more than tracking the video.
  constexpr int kMaxRows = 600;
  const cv::Size full = images[0].size();
  const double f = std::min(1.0, static_cast<double>(kMaxRows) / full.height);
  const cv::Size size(std::max(1, static_cast<int>(std::lround(f * full.width))),
                      std::max(1, static_cast<int>(std::lround(f * full.height))));
  // Image by image on OpenCV's threads (each image's result its own): at 1280x720 finding
  // the regions of 60 learning images took longer than tracking the clip.
  cv::parallel_for_(cv::Range(0, n), [&](const cv::Range& range) {
    for (int i = range.start; i < range.end; ++i) {
      cv::cvtColor(images[i], grey[i], cv::COLOR_BGR2GRAY);
      if (size != full) cv::resize(grey[i], grey[i], size, 0, 0, cv::INTER_AREA);
      cv::GaussianBlur(grey[i], grey[i], cv::Size(5, 5), 0);  // the sensor's and the codec's noise
    }
  });
  std::vector<cv::Mat> change(n - 1);  // |G_i+1 - G_i|
  for (int i = 0; i + 1 < n; ++i) cv::absdiff(grey[i], grey[i + 1], change[i]);
  // The noise: the change that 90% of the pixels stay under (people take fewer).
  std::vector<uint8_t> sample;
  for (const cv::Mat& c : change)
    for (int v = 0; v < c.rows; v += 4)
      for (int u = 0; u < c.cols; u += 4) sample.push_back(c.at<uint8_t>(v, u));
  const size_t p90 = sample.size() * 9 / 10;
  std::nth_element(sample.begin(), sample.begin() + p90, sample.end());
  const double threshold = std::max(6.0, 3.0 * sample[p90]);
  const int rows = size.height;
  const int join = std::max(1, static_cast<int>(std::lround(0.02 * rows)));  // 2% of the height
  const cv::Mat join_kernel = cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(2 * join + 1, 2 * join + 1));
  // Tight regions are grown by the 5x5 blur's reach and a pixel: what the blur spread.
  const cv::Mat tight_kernel = cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(7, 7));
  cv::parallel_for_(cv::Range(0, n), [&](const cv::Range& range) {
    for (int i = range.start; i < range.end; ++i) {
      cv::Mat m = cv::Mat::zeros(size, CV_8UC1);
      if (i > 0) m |= change[i - 1] > threshold;
      if (i + 1 < n) m |= change[i] > threshold;
      const cv::Mat changed = tight ? m.clone() : cv::Mat();  // the pieces before they are joined
      cv::dilate(m, m, join_kernel);  // a body's moving parts (head, arms, legs) join up
      RemoveSpecks(&m, min_area);
      // A region shaped like a standing person (at least 0.6 as tall as wide: a walker with
      // a shadow cast beside them) is filled to its hull: the still parts between moving
      // ones (a plain shirt) are the person's too. A wider one (a tape or flag in the wind, a
      // crowd) is not a person's and is left to the median, which handles it.
      std::vector<std::vector<cv::Point>> contours;
      cv::findContours(m, contours, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_SIMPLE);
      m.setTo(0);
      for (size_t k = 0; k < contours.size(); ++k) {
        const std::vector<cv::Point>& contour = contours[k];
        const cv::Rect box = cv::boundingRect(contour);
        if (box.height < 0.6 * box.width) continue;
        std::vector<cv::Point> hull, inside;
        if (tight) {
          // The hull of the changed pixels within the joined region: the person without
          // the joining's margin.
          cv::Mat region = cv::Mat::zeros(size, CV_8UC1);
          cv::drawContours(region, contours, static_cast<int>(k), 255, cv::FILLED);
          cv::findNonZero(region & changed, inside);
          if (inside.empty()) continue;
          cv::convexHull(inside, hull);
        } else {
          cv::convexHull(contour, hull);
        }
        cv::fillConvexPoly(m, hull, 255);
      }
      cv::dilate(m, m, tight ? tight_kernel : join_kernel);
      if (size != full) cv::resize(m, m, full, 0, 0, cv::INTER_NEAREST);
      moving[i] = m;
    }
  });
  return moving;
}

int MovingPersonHeight(const std::vector<cv::Mat>& moving) {
  std::vector<int> tallest;  // per image with a region
  for (const cv::Mat& m : moving) {
    cv::Mat labels, stats, centroids;
    const int count = cv::connectedComponentsWithStats(m, labels, stats, centroids, 8, CV_32S);
    int most = 0;
    for (int k = 1; k < count; ++k) most = std::max(most, stats.at<int>(k, cv::CC_STAT_HEIGHT));
    if (most > 0) tallest.push_back(most);
  }
  if (tallest.empty()) return 0;
  std::nth_element(tallest.begin(), tallest.begin() + tallest.size() / 2, tallest.end());
  // The regions were grown twice by 2% of the image's height, at the top and the bottom.
  return std::max(0, tallest[tallest.size() / 2] - static_cast<int>(std::lround(0.08 * moving[0].rows)));
}

namespace {
// How many of the masks (CV_8UC1) are non-zero at each pixel, CV_16UC1.
cv::Mat NonZeroCount(const std::vector<cv::Mat>& masks) {
  cv::Mat count = cv::Mat::zeros(masks[0].size(), CV_16UC1), one;
  for (const cv::Mat& mask : masks) {
    cv::compare(mask, 0, one, cv::CMP_NE);
    cv::bitwise_and(one, cv::Scalar::all(1), one);
    cv::add(count, one, count, cv::noArray(), CV_16U);
  }
  return count;
}
}  // namespace

cv::Mat MaskedMedian(const std::vector<cv::Mat>& images, const std::vector<cv::Mat>& use) {
  const int n = static_cast<int>(images.size());
  // Counts in 16 bits: learning_frames is at most 10000.
  JGPM_CHECK(n > 0 && n <= 30000 && (use.empty() || static_cast<int>(use.size()) == n));
  cv::Mat used(images[0].size(), CV_16UC3, cv::Scalar::all(n));
  if (!use.empty()) cv::merge(std::vector<cv::Mat>(3, NonZeroCount(use)), used);
  const cv::Mat all;  // an empty mask: every pixel
  cv::Mat median = cv::Mat::zeros(images[0].size(), CV_8UC3), trial, at_least, twice, take;
  cv::Mat count(images[0].size(), CV_16UC3);
  for (int bit = 128; bit >= 1; bit /= 2) {
    cv::bitwise_or(median, cv::Scalar::all(bit), trial);
    count.setTo(0);
    for (int k = 0; k < n; ++k) {
      cv::compare(images[k], trial, at_least, cv::CMP_GE);
      cv::bitwise_and(at_least, cv::Scalar::all(1), at_least);
      cv::add(count, at_least, count, use.empty() ? all : use[k], CV_16U);
    }
    // At least m - m/2 = ceil(m / 2) of them: twice the count at least m (a sum that
    // saturates is above any m).
    cv::add(count, count, twice);
    cv::compare(twice, used, take, cv::CMP_GE);
    cv::bitwise_and(take, cv::Scalar::all(bit), take);
    cv::bitwise_or(median, take, median);
  }
  return median;
}

void ForegroundExtractor::Learn(const std::vector<cv::Mat>& images, const std::vector<cv::Mat>& found) {
  JGPM_CHECK(!images.empty());
  const int n = static_cast<int>(images.size());
  const size_t pixels = static_cast<size_t>(width_) * height_;
  for (const cv::Mat& image : images) JGPM_CHECK(image.type() == CV_8UC3 && image.isContinuous() && image.total() == pixels);
  // Fewer than 10 images cannot spare any: the plain median.
  JGPM_CHECK(found.empty() || found.size() == images.size());
  const std::vector<cv::Mat> moving = !options_.exclude_moving || n < 10 ? std::vector<cv::Mat>()
                                      : found.empty()                    ? MovingRegions(images, options_.min_area)
                                                                         : found;
  // At least this many images must show a pixel still for their median to be its scene.
  const int enough = std::max(3, n / 20);
  // Each image's pixels that count: still ones, or all where too few images are still.
  std::vector<cv::Mat> use;
  cv::Mat unseen = cv::Mat::zeros(height_, width_, CV_8UC1);  // never still often enough
  if (!moving.empty()) {
    use.resize(n);
    for (int k = 0; k < n; ++k) cv::compare(moving[k], 0, use[k], cv::CMP_EQ);
    cv::compare(NonZeroCount(use), enough, unseen, cv::CMP_LT);  // still in too few
    for (cv::Mat& u : use) cv::bitwise_or(u, unseen, u);
  }
  cv::Mat median = MaskedMedian(images, use);
  // Some of those pixels were only in the regions' margin (the joining grows a region by
  // 2% of the height on each side, 10 px at 480 rows, where a distant walker is 15-20 px
  // wide): seen often enough beside the tight regions, their median is the scene.
  if (!moving.empty() && cv::countNonZero(unseen) > 0) {
    const std::vector<cv::Mat> tight = MovingRegions(images, options_.min_area, true);
    std::vector<cv::Mat> still(n);
    for (int k = 0; k < n; ++k) cv::compare(tight[k], 0, still[k], cv::CMP_EQ);
    cv::Mat seen;
    cv::compare(NonZeroCount(still), enough, seen, cv::CMP_GE);
    seen &= unseen;
    if (cv::countNonZero(seen) > 0) {
      MaskedMedian(images, still).copyTo(median, seen);
      unseen &= ~seen;
    }
  }
  // Where the scene never showed (a walker coming straight at the camera covers the same
  // pixels all along), the median is the person: filled in from the scene around instead.
  // A hole of people, not most of the image (a crowd, a moving camera: the median then).
  const int holes = cv::countNonZero(unseen);
  if (!moving.empty() && holes > 0 && holes < 0.25 * static_cast<double>(pixels)) {
    cv::Mat filled;
    cv::inpaint(median, unseen, filled, 5, cv::INPAINT_TELEA);
    median = filled;
  }
  SetBackground(median);
}

void ForegroundExtractor::SetBackground(const cv::Mat& background) {
  JGPM_CHECK(background.type() == CV_8UC3 && background.cols == width_ && background.rows == height_);
  background_ = background.clone();
  cv::cvtColor(background_, background_grey_, cv::COLOR_BGR2GRAY);
  if (options_.method == ForegroundMethod::kMog2) {
    auto mog2 = cv::createBackgroundSubtractorMOG2(500, options_.threshold, options_.shadows);
    // OpenCV's 0.9 makes anything that covered a pixel for 1-0.9^(1/rate) images (53 at
    // 0.002) part of the background: a person walking straight at a camera would fade.
    // At 0.6 the person must outweigh the scene first (about 460 images).
    mog2->setBackgroundRatio(0.6);
    subtractor_ = mog2;
    cv::Mat ignored;
    subtractor_->apply(background_, ignored, 1.0);  // the model is this image
  } else {
    auto knn = cv::createBackgroundSubtractorKNN(500, 25 * options_.threshold, options_.shadows);
    cv::Mat ignored;
    // KNN keeps samples of each pixel and counts one as the background only once it was
    // seen as such: it needs the scene shown over and over before it sees the person.
    for (int k = 0; k < 60; ++k) knn->apply(background_, ignored, -1);
    subtractor_ = knn;
  }
}

double ForegroundExtractor::Gain(const cv::Mat& bgr) const {
  // Median brightness ratio over a grid of pixels that are not near black.
  std::vector<float> ratios;
  ratios.reserve(static_cast<size_t>(width_ / 4 + 1) * (height_ / 4 + 1));
  cv::Mat grey;
  cv::cvtColor(bgr, grey, cv::COLOR_BGR2GRAY);
  for (int v = 0; v < height_; v += 4) {
    const uint8_t* now = grey.ptr<uint8_t>(v);
    const uint8_t* before = background_grey_.ptr<uint8_t>(v);
    for (int u = 0; u < width_; u += 4)
      if (before[u] >= 16 && before[u] <= 240) ratios.push_back(static_cast<float>(now[u]) / before[u]);
  }
  if (ratios.size() < 16) return 1;
  std::nth_element(ratios.begin(), ratios.begin() + ratios.size() / 2, ratios.end());
  const double gain = ratios[ratios.size() / 2];
  return std::clamp(gain, 0.25, 4.0);
}

cv::Mat ForegroundExtractor::Apply(const cv::Mat& bgr) {
  JGPM_CHECK(subtractor_ && bgr.type() == CV_8UC3 && bgr.cols == width_ && bgr.rows == height_);
  gain_ = options_.gain_compensation ? Gain(bgr) : 1.0;
  cv::Mat image;  // a new image: the caller's stays as it was (overlays show it)
  if (std::abs(gain_ - 1) > 0.01) {
    bgr.convertTo(image, -1, 1 / gain_);
  } else {
    image = bgr;
  }
  cv::Mat raw;
  subtractor_->apply(image, raw, options_.learning_rate);
  cv::Mat mask = raw == 255;  // shadows are 127
  for (const auto& [radius, op] : {std::pair{options_.open_px, cv::MORPH_OPEN}, {options_.close_px, cv::MORPH_CLOSE}}) {
    const int r = static_cast<int>(std::lround(radius));
    if (r < 1) continue;
    cv::morphologyEx(mask, mask, op, cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(2 * r + 1, 2 * r + 1)));
  }
  RemoveSpecks(&mask, options_.min_area);
  return mask;
}

void ForegroundShare::Add(const cv::Mat& mask) {
  shares_.push_back(static_cast<double>(cv::countNonZero(mask)) / static_cast<double>(mask.total()));
}

double ForegroundShare::Median() {
  if (shares_.empty()) return 0;
  std::nth_element(shares_.begin(), shares_.begin() + static_cast<std::ptrdiff_t>(shares_.size() / 2), shares_.end());
  return shares_[shares_.size() / 2];
}

void RemoveSpecks(cv::Mat* mask, double min_area) {
  cv::Mat labels, stats, centroids;
  const int n = cv::connectedComponentsWithStats(*mask, labels, stats, centroids, 8, CV_32S);
  std::vector<uint8_t> keep(n, 0);
  const auto box = [&stats](int k) {
    return cv::Rect(stats.at<int>(k, cv::CC_STAT_LEFT), stats.at<int>(k, cv::CC_STAT_TOP),
                    stats.at<int>(k, cv::CC_STAT_WIDTH), stats.at<int>(k, cv::CC_STAT_HEIGHT));
  };
  std::vector<int> large;
  for (int k = 1; k < n; ++k)
    if (stats.at<int>(k, cv::CC_STAT_AREA) >= min_area * mask->total()) keep[k] = 255, large.push_back(k);
  // A small piece under a larger blob (kFootGap) is part of it: a foot under a table's edge.
  for (int k = 1; k < n; ++k) {
    if (keep[k]) continue;
    const cv::Rect piece = box(k);
    for (const int l : large) {
      const cv::Rect big = box(l);
      const int gap = static_cast<int>(kFootGap * big.height);
      const int below = piece.y - (big.y + big.height);
      const int overlap = std::min(piece.x + piece.width, big.x + big.width) - std::max(piece.x, big.x);
      if (below >= 0 && below <= gap && 2 * overlap >= piece.width) {
        keep[k] = 255;
        break;
      }
    }
  }
  for (int v = 0; v < mask->rows; ++v) {
    const int* l = labels.ptr<int>(v);
    uint8_t* m = mask->ptr<uint8_t>(v);
    for (int u = 0; u < mask->cols; ++u) m[u] = keep[l[u]];
  }
}

}  // namespace jgpm
