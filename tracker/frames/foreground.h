// Foreground masks from colour images, where nobody hands the tracker a clean silhouette:
// OpenCV's background subtraction (MOG2 or KNN, shadows suppressed), started from a picture
// of the empty scene, then a morphological clean-up that removes specks.
//
// What is kept: every connected component larger than a speck. Choosing the person among
// them is left to the tracker, which knows where it expects the person (it only counts
// foreground inside the predicted region; tracker/filter/observation.h) and, at the start, finds
// the blob the cameras agree on (tracker/filter/person_locator.h): a rule here such as "the
// largest blob" would lose the person to anything bigger passing by.
//
// Why it is started from a picture of the scene: both subtractors learn the background
// from whatever they see first, and a person walking in view from the first frame would
// become part of it (and leave a ghost). The picture is a given empty-scene image
// (`--background`), or the per-pixel median of `learning_frames` images: spread over the
// whole input for a file or folder, the first ones for a live camera. The median is the
// scene wherever the person covers a pixel for less than half of those images: true for a
// walk across the view over a few seconds; a person who stands still, or walks straight
// at a camera through most of the images, needs a given background or the learning frames
// with nobody in view (a live camera: step out of view for the first 2 s).
//
// A global change of light (a cloud, auto exposure) would turn the whole image into
// foreground: each image is first divided by its brightness gain against the background,
// the median ratio over the image, which the person (a minority of pixels) does not move.
#pragma once

#include <string>
#include <vector>

#include <opencv2/core/mat.hpp>
#include <opencv2/video/background_segm.hpp>

namespace jgpm {

enum class ForegroundMethod { kMog2, kKnn };

struct ForegroundOptions {
  ForegroundMethod method = ForegroundMethod::kMog2;
  int learning_frames = 60;      // images the scene's median is taken over
  double learning_rate = 0.002;  // then how fast the model follows slow changes, per image
  double threshold = 16;         // MOG2: squared Mahalanobis distance; KNN: its x25 squared
                                 // distance (400 at 16), as OpenCV's defaults
  bool shadows = true;           // pixels darker than the background in its colour: not
                                 // foreground
  bool gain_compensation = true;
  double open_px = 1;            // clean-up radii at 240 rows (scaled with the image): open
  double close_px = 1;           // removes specks, close joins a limb cut by a thin gap
  double min_area = 0.0005;      // components smaller than this fraction of the image
                                 // (38 pixels at 320x240) are specks

  bool Check(std::string* why) const;
};

class ForegroundExtractor {
 public:
  ForegroundExtractor(const ForegroundOptions& options, int width, int height);
  // The scene without the person: the median of `images` (BGR, the extractor's size).
  void Learn(const std::vector<cv::Mat>& images);
  // The scene from a given empty-scene image.
  void SetBackground(const cv::Mat& background);
  const cv::Mat& background() const { return background_; }
  // CV_8UC1 mask, 255 = the person; all zero when nobody is there. Learns the background
  // slowly as it goes. Learn or SetBackground first.
  cv::Mat Apply(const cv::Mat& bgr);
  // The brightness gain of the last image against the background (1 when compensation is
  // off).
  double last_gain() const { return gain_; }

 private:
  double Gain(const cv::Mat& bgr) const;

  ForegroundOptions options_;
  int width_, height_;
  cv::Ptr<cv::BackgroundSubtractor> subtractor_;
  cv::Mat background_, background_grey_;
  double gain_ = 1;
};

// Removes the connected components smaller than `min_area` of the image from a binary
// mask (255 = foreground), in place.
void RemoveSpecks(cv::Mat* mask, double min_area);

}  // namespace jgpm
