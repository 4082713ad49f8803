// What makes a synthetic clip harder than a perfect segmentation: sensor noise, eroded or
// dilated and holed masks, moving background clutter, a change of lighting, dropped frames.
#pragma once

#include <random>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

namespace jgpm {

struct ClipDegradations {
  double sensor_noise = 3;     // std of per-pixel Gaussian noise in the video, grey levels
  double mask_noise_px = 0;    // observed masks: each frame eroded or dilated by up to this
  int holes = 0;               // observed masks: holes (radius 2-5 px) punched per frame
  int clutter_blobs = 0;       // coloured blobs moving over the background (video + masks)
  double lighting_gain = 1;    // brightness at the end: ramps from 1 over the middle third
  double drop_rate = 0;        // probability that a frame (not the first) is dropped

  bool Check(std::string* why) const;
  bool Any() const;
};

// Coloured ellipses drifting across one camera's image, bouncing at the borders.
class MovingClutter {
 public:
  // `blobs` blobs placed at random (drawn from `rng` in a fixed order).
  MovingClutter(int blobs, int width, int height, std::mt19937_64* rng);
  // Moves every blob one clip frame on (dropped frames included).
  void Step();
  // Draws the blobs into `labels` (CV_8UC1 of the image size): 1 + blob index, 0 elsewhere.
  void Draw(cv::Mat* labels) const;
  // BGR colour of the blob a label stands for (label >= 1).
  const cv::Scalar& Colour(int label) const { return blobs_[label - 1].colour; }

 private:
  struct Blob {
    cv::Point2d at, velocity;
    cv::Size2d axes;
    double angle_deg;
    cv::Scalar colour;
  };
  std::vector<Blob> blobs_;
  int width_, height_;
};

// Brightness gain at clip time fraction s in [0, 1]: 1, then a ramp to `final_gain` over
// the middle third.
double LightingGain(double s, double final_gain);

// The mask as a segmentation would deliver it: eroded or dilated, holed, with the clutter
// (`clutter` nonzero where a blob is).
cv::Mat DegradeMask(const cv::Mat& mask, const cv::Mat& clutter, const ClipDegradations& degradations,
                    std::mt19937_64* rng);

}  // namespace jgpm
