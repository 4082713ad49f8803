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
// (`--background`), or learnt from `learning_frames` images: spread over the whole input
// for a file or folder, the first ones for a live camera. Learnt: each pixel's median over
// the images where it is not in a moving region. A plain median is the scene only where
// the person covers a pixel in under half of the images, which a walker coming straight
// at a camera does not: the median held the walker (mask IoU 0.19-0.37 against the exact
// silhouettes in the front cameras of the held-out clips, against 0.76-0.83 from the empty
// room). A moving region is where an image (grey, blurred over 5x5 px against the sensor's
// and the codec's noise) differs from the one before or after it by three times what 90%
// of the pixels differ by (the noise; people cover less) and at least 6 grey levels, pieces within
// 2% of the image's height joined, each shaped like a standing person (at least 0.6 as
// tall as wide, a shadow beside them included) filled to its convex hull (a plain shirt
// does not change between images, the limbs around it do) and grown by that 2% again;
// wider ones (a tape in the wind, a crowd) are left to the median. (The ratio was chosen
// on the realism tuning clips: 1.2 and 0.8 left a walker with their shadow to the median,
// mask IoU 0.16 in 07_03's front camera against 0.38 at 0.6 and 0.4. With no shape rule at
// all, the tape fluttering over vtest.avi's plaza was inpainted and became foreground.) A pixel still
// in fewer than a twentieth of the images (at least 3) was hardly ever the scene (the walker
// coming at the camera covers the same pixels all along, far or near), or was only in the
// regions' margin: a distant walker 15-20 px wide gets a region 55-60 px wide. Those pixels
// get a second look with tight regions (the hull of each region's changed pixels grown by
// 3 px, the blur's reach): their median over the images where the tight regions leave them
// still, when at least as many do. What is still unseen is filled in from the scene around
// it (OpenCV's inpainting), not the plain median, which is the person (unless that is a
// quarter of the image or more: a crowd, a moving camera). Filling in the whole margin left
// a ghost as wide again beside a slow walker coming at the camera (mask IoU 0.36-0.45
// against 0.75-0.80 now, and the front cameras of foreground_test 0.66 and 0.62 against
// 0.83 and 0.80, the empty room 0.85 and 0.86). Fewer than 10
// images: the plain median. A person who stands still through the images is not moving
// either: that needs a given background.
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
  // Clean-up radii, px at any image size: open removes specks, close joins a limb cut by a
  // thin gap. Not scaled with the image: sensor and codec specks are a pixel or two
  // whatever the size (bigger ones go by min_area), and the working resolution keeps
  // people at most 200 px tall (tracker/frames/working_resolution.h), while people far
  // from a surveillance camera are 30-60 px tall with limbs 2-3 px wide, which the opening
  // of radius 2 at 480 rows that scaling gave erased, and the closing of radius 2 joined
  // to their shadows and neighbours: the 640x480 5-walker plaza clip's MOTA from its
  // video rose from 0.46 to 0.75 (2 seeds; 0.71 with the closing still scaled), and
  // vtest.avi's HOG boxes with a tracked person on them from 0.897 to 0.921.
  double open_px = 1;
  double close_px = 1;
  double min_area = 0.0005;      // components smaller than this fraction of the image
                                 // (38 pixels at 320x240) are specks
  bool exclude_moving = true;    // learning: the median leaves out moving regions

  bool Check(std::string* why) const;
};

class ForegroundExtractor {
 public:
  ForegroundExtractor(const ForegroundOptions& options, int width, int height);
  // The scene without the person: the median of `images` (BGR, the extractor's size).
  // `moving`: their MovingRegions when already found (else found here).
  void Learn(const std::vector<cv::Mat>& images, const std::vector<cv::Mat>& moving = {});
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

// Each pixel's and channel's median over the images (CV_8UC3) whose `use` (CV_8UC1,
// non-zero where it counts; empty: all count) holds it: of its m values the (m/2)-th
// smallest from 0, as nth_element gives; 255 where no image counts. Found a bit at a time
// from the top, the largest v with at least m - m/2 values >= v, with whole-image
// operations (per pixel with nth_element it was about 0.5 s of CPU for a 640x480 video's
// 60 images, 16% of `jgpm`'s time in calibrate_walkers_cli_test).
cv::Mat MaskedMedian(const std::vector<cv::Mat>& images, const std::vector<cv::Mat>& use = {});

// Per image of a sequence (BGR, time order): 255 where something moves (see above).
// `tight`: each region the hull of its changed pixels grown by 3 px (the blur's reach),
// not of the joined pieces grown by 2% of the height.
std::vector<cv::Mat> MovingRegions(const std::vector<cv::Mat>& images, double min_area, bool tight = false);
// How tall the people walking through are, px, from a sequence's MovingRegions (0: nobody):
// over the images with a moving region, the median of their tallest, less the regions'
// growth. Not the tallest of all: people at different depths stack in a view from above,
// and their regions merge now and then (vtest.avi's reached 5 people's height).
int MovingPersonHeight(const std::vector<cv::Mat>& moving);

// How much of a camera's masks is foreground, frame after frame: the median share of their
// pixels. A fixed camera's is its people, a few percent; most of the image, most of the
// time, is a camera that moves (`calibrate --walkers` refuses it, `track` says so).
class ForegroundShare {
 public:
  void Add(const cv::Mat& mask);  // CV_8UC1, non-zero = foreground
  bool empty() const { return shares_.empty(); }
  double Median();  // 0 when empty

 private:
  std::vector<double> shares_;
};

// Removes the connected components smaller than `min_area` of the image from a binary
// mask (255 = foreground), in place, but for those under a larger one: at most kFootGap
// of its height below it, with at least half of their columns within its columns. A foot
// seen under a table's edge is a piece of 20-30 px at 320x240, and without it a camera
// alone places the walker by the head (the locator) and the body slides along the line
// of sight (35_28-tune-trousers-occl from its video, 4 seeds: 132.4 -> 73.3 mm,
// bodytrack's 14 joints; from its masks 54.5). Chosen on the realism tuning clips from
// their videos (4 seeds, mean of the 6 clips): 0 (only a piece right under its box)
// 105.2 mm, 0.25 96.2, 0.4 95.8, 0.8 95.8; the smallest of the plateau, which keeps the
// fewest stray pieces below people.
constexpr double kFootGap = 0.4;
void RemoveSpecks(cv::Mat* mask, double min_area);

}  // namespace jgpm
