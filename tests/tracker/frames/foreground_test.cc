// Background subtraction against the renderer's exact silhouettes: a clip of the test
// subject is rendered (textured room, sensor noise, MJPG; and a degraded one with moving
// clutter and a brightening light), its videos are turned into masks as a real video's
// would be, and the masks are compared with the exact masks of the same frames: IoU in
// the person's neighbourhood (the exact silhouette's box grown by half its height; clutter
// elsewhere is the tracker's to ignore, as in the clip's own degraded masks).
#include "tracker/frames/foreground.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <optional>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "io/base/error.h"
#include "io/mocap/amc.h"
#include "io/mocap/asf.h"
#include "test_support.h"
#include "tracker/clip/synthetic_clip.h"
#include "tracker/frames/clip_source.h"

namespace jgpm {
namespace {
namespace fs = std::filesystem;

fs::path Render(const test::TempDir& dir, const std::string& name, const ClipDegradations& degradations, int cameras) {
  const ClipSource source = {(test::CmuRoot() / "subjects/07/07.asf").string(),
                             (test::CmuRoot() / "subjects/07/07_01.amc").string()};
  const Skeleton skeleton = ReadAsf(source.asf);
  const Motion motion = ReadAmc(source.amc, skeleton);
  ClipOptions clip;
  clip.rig.num_cameras = cameras;
  clip.rig.width = 320;
  clip.rig.height = 240;
  clip.degradations = degradations;
  clip.contact_sheet = false;
  const fs::path out = dir.path() / name;
  RenderClip(skeleton, motion, source, {}, clip, out.string());
  return out;
}

double Iou(const cv::Mat& computed, const cv::Mat& exact) {
  cv::Rect box = cv::boundingRect(exact);
  const int grow = box.height / 2;
  box = cv::Rect(box.x - grow, box.y - grow, box.width + 2 * grow, box.height + 2 * grow) &
        cv::Rect(0, 0, exact.cols, exact.rows);
  const cv::Mat a = computed(box), b = exact(box);
  const double both = cv::countNonZero(a & b), either = cv::countNonZero(a | b);
  return either > 0 ? both / either : 1.0;
}

// Mean and worst IoU of the computed masks against the exact ones, per camera, over the
// frames not dropped.
struct Overlap {
  double mean = 0, worst = 1;
  std::vector<double> camera_mean;  // per camera
};
// `options` empty: the clip's own degraded masks (the renderer's model of a segmentation).
Overlap Measure(const fs::path& clip, const std::optional<ForegroundOptions>& options, bool learn = false) {
  ClipFrameSourceOptions computed_options;
  computed_options.foreground = options;
  computed_options.learn_background = learn;
  ClipFrameSource computed(clip, computed_options);
  ClipFrameSourceOptions exact_options;
  exact_options.exact_masks = true;
  ClipFrameSource exact(clip, exact_options);
  Frame a, b;
  Overlap o;
  int n = 0;
  while (computed.Next(&a) && exact.Next(&b)) {
    EXPECT_EQ(a.index, b.index);
    if (a.dropped) continue;
    o.camera_mean.resize(a.masks.size());
    for (size_t c = 0; c < a.masks.size(); ++c) {
      const double iou = Iou(a.masks[c], b.masks[c]);
      o.mean += iou;
      o.camera_mean[c] += iou;
      o.worst = std::min(o.worst, iou);
      ++n;
    }
  }
  o.mean /= n;
  for (double& m : o.camera_mean) m /= n / static_cast<double>(o.camera_mean.size());
  return o;
}

struct Clips {
  test::TempDir dir;
  fs::path clean, degraded;
};
const Clips& Shared() {
  static Clips clips;
  static const bool made = [] {
    clips.clean = Render(clips.dir, "clean", ClipDegradations{}, 4);
    ClipDegradations d;
    d.clutter_blobs = 3;
    d.lighting_gain = 1.4;
    d.drop_rate = 0.05;
    d.mask_noise_px = 1;
    d.holes = 2;
    clips.degraded = Render(clips.dir, "degraded", d, 2);
    return true;
  }();
  (void)made;
  return clips;
}

TEST(Foreground, Mog2MasksOverlapTheExactSilhouettes) {
  const Overlap clean = Measure(Shared().clean, ForegroundOptions{});
  std::printf("MOG2, clean clip (4 cameras), from the empty room: IoU mean %.3f, worst %.3f\n", clean.mean, clean.worst);
  EXPECT_GT(clean.mean, 0.85);
  EXPECT_GT(clean.worst, 0.6);
}

// The room learnt from the clip's own frames, with no picture of it: in the side cameras as
// good as the picture; in the front ones, where the walker comes straight at the camera and
// covers the same pixels all along (the plain per-pixel median holds the walker: 0.29 and
// 0.44 against 0.85 from the picture), 0.83 and 0.80 (measured): the pixels beside the
// walker, in the moving regions' margin, are their median where the tight regions leave
// them still; only those the walker always covered are filled in from the room around.
// Filling in the whole margin gave 0.66 and 0.62.
TEST(Foreground, TheRoomLearntFromTheVideoIsAsGoodAsAPictureOfIt) {
  const Overlap room = Measure(Shared().clean, ForegroundOptions{});
  const Overlap learnt = Measure(Shared().clean, ForegroundOptions{}, true);
  ForegroundOptions plain;
  plain.exclude_moving = false;
  const Overlap median = Measure(Shared().clean, plain, true);
  for (size_t c = 0; c < room.camera_mean.size(); ++c) {
    std::printf("camera %zu: IoU from the room %.3f, learnt %.3f, plain median %.3f\n", c, room.camera_mean[c],
                learnt.camera_mean[c], median.camera_mean[c]);
    EXPECT_GT(learnt.camera_mean[c], room.camera_mean[c] - 0.1) << c;
  }
  EXPECT_LT(*std::min_element(median.camera_mean.begin(), median.camera_mean.end()),
            *std::min_element(learnt.camera_mean.begin(), learnt.camera_mean.end()) - 0.15);  // what it fixes
}

TEST(Foreground, KnnMasksOverlapTheExactSilhouettes) {
  ForegroundOptions knn;
  knn.method = ForegroundMethod::kKnn;
  const Overlap clean = Measure(Shared().clean, knn);
  std::printf("KNN, clean clip (4 cameras): IoU mean %.3f, worst %.3f\n", clean.mean, clean.worst);
  EXPECT_GT(clean.mean, 0.85);
  EXPECT_GT(clean.worst, 0.6);
}

TEST(Foreground, HoldsUnderClutterAndALightingChange) {
  const Overlap degraded = Measure(Shared().degraded, ForegroundOptions{});
  ForegroundOptions uncompensated;
  uncompensated.gain_compensation = false;
  const Overlap without = Measure(Shared().degraded, uncompensated);
  const Overlap observed = Measure(Shared().degraded, std::nullopt);
  std::printf("MOG2, degraded clip (clutter, light to 1.4): IoU mean %.3f, worst %.3f; without gain compensation "
              "%.3f, %.3f; the clip's own degraded masks %.3f, %.3f\n",
              degraded.mean, degraded.worst, without.mean, without.worst, observed.mean, observed.worst);
  EXPECT_GT(degraded.mean, 0.5);
  EXPECT_GT(degraded.mean, observed.mean - 0.05);  // as good as the renderer's model of a segmentation
  EXPECT_GT(degraded.mean, without.mean + 0.1);  // the compensation is what holds under the change
}

// A person 60 px tall in a 640x480 view from above (a surveillance camera's far walker):
// legs and arms 3 px wide. The clean-up must keep them: an opening scaled with the image
// (radius 2 at 480 rows) erased them.
TEST(Foreground, KeepsTheLimbsOfASmallPersonInALargeImage) {
  cv::Mat background(480, 640, CV_8UC3), frame;
  cv::randu(background, cv::Scalar(90, 100, 110), cv::Scalar(130, 140, 150));  // a textured floor
  frame = background.clone();
  cv::Mat drawn = cv::Mat::zeros(480, 640, CV_8UC1);
  const cv::Scalar coat(40, 30, 160);
  cv::circle(drawn, {320, 205}, 4, 255, cv::FILLED);                    // head
  cv::rectangle(drawn, cv::Rect(315, 210, 11, 22), 255, cv::FILLED);    // torso
  cv::rectangle(drawn, cv::Rect(315, 232, 3, 28), 255, cv::FILLED);     // legs, 3 px wide
  cv::rectangle(drawn, cv::Rect(323, 232, 3, 28), 255, cv::FILLED);
  cv::rectangle(drawn, cv::Rect(311, 212, 3, 18), 255, cv::FILLED);     // arm
  frame.setTo(coat, drawn);
  ForegroundExtractor extractor(ForegroundOptions{}, 640, 480);
  extractor.SetBackground(background);
  const cv::Mat mask = extractor.Apply(frame);
  cv::Mat legs = cv::Mat::zeros(480, 640, CV_8UC1);
  legs(cv::Rect(0, 240, 640, 20)).setTo(255);
  legs &= drawn;
  const double kept = cv::countNonZero(mask & legs) / static_cast<double>(cv::countNonZero(legs));
  EXPECT_GT(kept, 0.8) << "of the legs' pixels";
  EXPECT_GT(cv::countNonZero(mask & drawn), 0.8 * cv::countNonZero(drawn));
  EXPECT_LT(cv::countNonZero(mask & ~drawn), 0.1 * cv::countNonZero(drawn));  // and nothing else
}

TEST(Foreground, RemoveSpecksKeepsEveryBlobButSpecks) {
  cv::Mat mask = cv::Mat::zeros(240, 320, CV_8UC1);
  cv::rectangle(mask, cv::Rect(100, 40, 40, 150), 255, cv::FILLED);  // the body
  cv::rectangle(mask, cv::Rect(145, 60, 4, 10), 255, cv::FILLED);    // a hand cut off, 40 px
  cv::rectangle(mask, cv::Rect(280, 200, 30, 30), 255, cv::FILLED);  // someone else
  cv::rectangle(mask, cv::Rect(20, 20, 6, 6), 255, cv::FILLED);      // a speck, 36 px
  RemoveSpecks(&mask, ForegroundOptions{}.min_area);
  EXPECT_EQ(cv::countNonZero(mask), 40 * 150 + 4 * 10 + 30 * 30);
  EXPECT_EQ(mask.at<uint8_t>(22, 22), 0);
}

// A piece too small to be anything alone is kept when it lies under a blob, within its
// columns and a little below it: a foot seen under a table's edge. The same piece farther
// down, or beside the blob, is a speck.
TEST(Foreground, RemoveSpecksKeepsAFootUnderABlob) {
  cv::Mat mask = cv::Mat::zeros(240, 320, CV_8UC1);
  cv::rectangle(mask, cv::Rect(100, 40, 40, 100), 255, cv::FILLED);  // the body above a table, to row 139
  const cv::Rect foot(110, 160, 10, 3), far(110, 185, 10, 3), beside(150, 160, 10, 3), across(138, 160, 10, 3);
  for (const cv::Rect& r : {foot, far, beside, across}) cv::rectangle(mask, r, 255, cv::FILLED);
  RemoveSpecks(&mask, ForegroundOptions{}.min_area);
  // The foot 20 px under a 100 px blob; the far one 45 px (more than kFootGap of it); the
  // one beside it out of its columns; the one across its edge with 2 of its 10 columns in.
  EXPECT_EQ(cv::countNonZero(mask(foot)), 30);
  EXPECT_EQ(cv::countNonZero(mask(far)), 0);
  EXPECT_EQ(cv::countNonZero(mask(beside)), 0);
  EXPECT_EQ(cv::countNonZero(mask(across)), 0);
  EXPECT_EQ(cv::countNonZero(mask), 40 * 100 + 30);
}

TEST(Foreground, LearnTakesThePerPixelMedian) {
  std::vector<cv::Mat> images;
  for (int k = 0; k < 5; ++k) images.emplace_back(4, 4, CV_8UC3, cv::Scalar(10 * k, 100, 200 - k));
  images[0].at<cv::Vec3b>(1, 1) = cv::Vec3b(255, 255, 255);  // someone passing
  ForegroundExtractor extractor(ForegroundOptions{}, 4, 4);
  extractor.Learn(images);
  EXPECT_EQ(extractor.background().at<cv::Vec3b>(0, 0), cv::Vec3b(20, 100, 198));
  EXPECT_EQ(extractor.background().at<cv::Vec3b>(1, 1), cv::Vec3b(30, 100, 198));
}

// Against each pixel's nth_element over the images it counts in: random images and masks,
// from one image to more than 255.
TEST(Foreground, MaskedMedianIsEachPixelsMedian) {
  cv::RNG rng(5);
  for (const int n : {1, 2, 7, 60, 300}) {
    std::vector<cv::Mat> images(n), use(n);
    for (int k = 0; k < n; ++k) {
      images[k].create(9, 13, CV_8UC3);
      rng.fill(images[k], cv::RNG::UNIFORM, 0, 256);
      use[k].create(9, 13, CV_8UC1);
      rng.fill(use[k], cv::RNG::UNIFORM, 0, 3);  // 0 (left out) a third of the time
    }
    use[0].setTo(7);  // every pixel counted somewhere
    for (const bool masked : {false, true}) {
      const cv::Mat median = MaskedMedian(images, masked ? use : std::vector<cv::Mat>());
      for (int p = 0; p < 9 * 13; ++p) {
        for (int c = 0; c < 3; ++c) {
          std::vector<uint8_t> values;
          for (int k = 0; k < n; ++k)
            if (!masked || use[k].data[p]) values.push_back(images[k].data[3 * p + c]);
          std::nth_element(values.begin(), values.begin() + values.size() / 2, values.end());
          ASSERT_EQ(median.data[3 * p + c], values[values.size() / 2]) << n << " images, pixel " << p << " " << masked;
        }
      }
    }
  }
}

// The scene from many images (learning_frames goes to 10000): a pixel that a walker covers
// in the first 2600 of 5200 is the scene's in the others (the still images were counted
// 255 at a time in 16 bits, and past 257 of them every pixel looked never still).
TEST(Foreground, LearnCountsStillImagesOfAnyNumber) {
  const int n = 5200;
  std::vector<cv::Mat> images, moving;
  for (int k = 0; k < n; ++k) {
    images.emplace_back(2, 2, CV_8UC3, cv::Scalar(50, 60, 70));
    moving.push_back(cv::Mat::zeros(2, 2, CV_8UC1));
    if (k < n / 2) {
      images.back().at<cv::Vec3b>(0, 0) = cv::Vec3b(200, 200, 200);
      moving.back().at<uint8_t>(0, 0) = 255;
    }
  }
  ForegroundExtractor extractor(ForegroundOptions{}, 2, 2);
  extractor.Learn(images, moving);
  EXPECT_EQ(extractor.background().at<cv::Vec3b>(0, 0), cv::Vec3b(50, 60, 70));
}

TEST(Foreground, RefusesBadOptions) {
  ForegroundOptions o;
  o.learning_frames = 0;
  EXPECT_THROW(ForegroundExtractor(o, 32, 32), InputError);
}

}  // namespace
}  // namespace jgpm
