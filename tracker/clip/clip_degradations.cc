#include "tracker/clip/clip_degradations.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <opencv2/imgproc.hpp>

namespace jgpm {

bool ClipDegradations::Check(std::string* why) const {
  auto fail = [&](const std::string& what) { if (why) *why = what; return false; };
  if (!(sensor_noise >= 0 && sensor_noise <= 100)) return fail("sensor noise: expected 0 to 100 grey levels");
  if (!(mask_noise_px >= 0 && mask_noise_px <= 20)) return fail("mask noise: expected 0 to 20 px");
  if (holes < 0 || holes > 100) return fail("holes: expected 0 to 100 per frame");
  if (clutter_blobs < 0 || clutter_blobs > 50) return fail("clutter: expected 0 to 50 blobs");
  if (!(lighting_gain >= 0.1 && lighting_gain <= 3)) return fail("lighting gain: expected 0.1 to 3");
  if (!(drop_rate >= 0 && drop_rate < 1)) return fail("drop rate: expected 0 <= rate < 1");
  return true;
}

bool ClipDegradations::Any() const {
  return mask_noise_px > 0 || holes > 0 || clutter_blobs > 0 || lighting_gain != 1 || drop_rate > 0;
}

MovingClutter::MovingClutter(int blobs, int width, int height, std::mt19937_64* rng) : width_(width), height_(height) {
  std::uniform_real_distribution<double> uniform(0, 1);
  for (int b = 0; b < blobs; ++b) {
    const double speed = 0.5 + 2 * uniform(*rng), heading = 2 * std::numbers::pi * uniform(*rng);
    blobs_.push_back({{width * uniform(*rng), height * (0.2 + 0.7 * uniform(*rng))},
                      {speed * std::cos(heading), speed * std::sin(heading)},
                      {width * (0.02 + 0.04 * uniform(*rng)), height * (0.03 + 0.05 * uniform(*rng))},
                      180 * uniform(*rng),
                      cv::Scalar(255 * uniform(*rng), 255 * uniform(*rng), 255 * uniform(*rng))});
  }
}

void MovingClutter::Step() {
  for (Blob& blob : blobs_) {
    blob.at += blob.velocity;
    if (blob.at.x < 0 || blob.at.x > width_) blob.velocity.x = -blob.velocity.x;
    if (blob.at.y < 0 || blob.at.y > height_) blob.velocity.y = -blob.velocity.y;
  }
}

void MovingClutter::Draw(cv::Mat* labels) const {
  labels->setTo(0);
  for (size_t b = 0; b < blobs_.size(); ++b) {
    const Blob& blob = blobs_[b];
    cv::ellipse(*labels, blob.at, blob.axes, blob.angle_deg, 0, 360, cv::Scalar(1 + static_cast<double>(b)), -1);
  }
}

double LightingGain(double s, double final_gain) {
  const double r = std::clamp((s - 1.0 / 3) * 3, 0.0, 1.0);
  return 1 + (final_gain - 1) * r;
}

cv::Mat DegradeMask(const cv::Mat& mask, const cv::Mat& clutter, const ClipDegradations& deg, std::mt19937_64* rng) {
  std::uniform_real_distribution<double> uniform(0, 1);
  cv::Mat observed = mask.clone();
  if (deg.mask_noise_px > 0) {
    const int r = static_cast<int>(std::lround(deg.mask_noise_px * uniform(*rng)));
    if (r > 0) {
      const cv::Mat kernel = cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(2 * r + 1, 2 * r + 1));
      if (uniform(*rng) < 0.5) cv::erode(observed, observed, kernel);
      else cv::dilate(observed, observed, kernel);
    }
  }
  if (deg.holes > 0) {
    std::vector<cv::Point> inside;
    cv::findNonZero(mask, inside);
    for (int h = 0; h < deg.holes && !inside.empty(); ++h) {
      const cv::Point at = inside[static_cast<size_t>(uniform(*rng) * inside.size()) % inside.size()];
      cv::circle(observed, at, 2 + static_cast<int>(4 * uniform(*rng)), cv::Scalar(0), -1);
    }
  }
  observed.setTo(255, clutter);
  return observed;
}

}  // namespace jgpm
