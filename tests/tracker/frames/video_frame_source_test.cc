// Several cameras' images paired into frames by time: the first camera sets the frames,
// each other camera gives its image within half a frame period, and a frame some camera
// did not see is handed out as dropped (predicted by the tracker), never as an empty view.
#include "tracker/frames/video_frame_source.h"

#include <random>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "io/base/error.h"
#include "tracker/frames/working_resolution.h"

namespace jgpm {
namespace {

// Images at given times; pixel value = the image's position in the list.
class ScriptedSource : public ImageSource {
 public:
  ScriptedSource(std::vector<double> times, double fps, int width = 32, int height = 24)
      : times_(std::move(times)), fps_(fps), width_(width), height_(height) {}
  const std::string& name() const override { return name_; }
  int width() const override { return width_; }
  int height() const override { return height_; }
  double fps() const override { return fps_; }
  int NumFrames() const override { return static_cast<int>(times_.size()); }
  bool Read(Image* image) override {
    if (next_ >= times_.size()) return false;
    image->bgr = cv::Mat(height_, width_, CV_8UC3, cv::Scalar::all(static_cast<double>(next_)));
    image->time_s = times_[next_];
    image->index = static_cast<int>(next_);
    ++next_;
    return true;
  }
  std::vector<cv::Mat> Sample(int) override { return {cv::Mat(height_, width_, CV_8UC3, cv::Scalar::all(200))}; }

 private:
  std::string name_ = "scripted";
  std::vector<double> times_;
  double fps_;
  int width_, height_;
  size_t next_ = 0;
};

Camera CameraOf(int width, int height) {
  Camera camera;
  camera.width = width;
  camera.height = height;
  camera.fx = camera.fy = 30;
  return camera;
}

TEST(VideoFrameSource, PairsImagesByTimeAndPredictsWhatOneCameraMissed) {
  // Camera 0 at 10 frames/s; camera 1 offset by 20 ms, missing the image near 0.3 s, with
  // an extra early image (before camera 0 started) and one 60 ms off (more than 50 ms).
  std::vector<std::unique_ptr<ImageSource>> sources;
  sources.push_back(std::make_unique<ScriptedSource>(std::vector<double>{0.0, 0.1, 0.2, 0.3, 0.4, 0.5}, 10));
  sources.push_back(std::make_unique<ScriptedSource>(std::vector<double>{-0.2, 0.02, 0.12, 0.22, 0.46, 0.52}, 10));
  VideoFrameSource source(std::move(sources), {CameraOf(32, 24), CameraOf(32, 24)}, {});
  const std::vector<bool> dropped = {false, false, false, true, true, false};
  const std::vector<int> paired = {1, 2, 3, -1, -1, 5};  // camera 1's image for each frame
  Frame frame;
  for (int k = 0; k < 6; ++k) {
    ASSERT_TRUE(source.Next(&frame));
    EXPECT_EQ(frame.index, k);
    EXPECT_NEAR(frame.time_s, 0.1 * k, 1e-12);
    EXPECT_EQ(frame.dropped, dropped[k]) << "frame " << k;
    if (frame.dropped) {
      EXPECT_TRUE(frame.masks[0].empty() && frame.masks[1].empty());
      continue;
    }
    EXPECT_EQ(frame.images[1].at<cv::Vec3b>(0, 0)[0], paired[k]) << "frame " << k;
    EXPECT_EQ(frame.masks[0].type(), CV_8UC1);
  }
  EXPECT_FALSE(source.Next(&frame));
  EXPECT_EQ(source.unpaired(), 2);
}

TEST(VideoFrameSource, PairsOnTheRigsClockWhenACamerasVideoStartedLate) {
  // Camera 1's video started 0.3 s after camera 0's (clock_offset_s 0.3): its image at its
  // own 0.0 s is camera 0's at 0.3 s. Camera 0's first three frames have no partner.
  std::vector<std::unique_ptr<ImageSource>> sources;
  sources.push_back(std::make_unique<ScriptedSource>(std::vector<double>{0.0, 0.1, 0.2, 0.3, 0.4, 0.5}, 10));
  sources.push_back(std::make_unique<ScriptedSource>(std::vector<double>{0.0, 0.1, 0.2, 0.3}, 10));
  Camera late = CameraOf(32, 24);
  late.clock_offset_s = 0.3;
  VideoFrameSource source(std::move(sources), {CameraOf(32, 24), late}, {});
  Frame frame;
  for (int k = 0; k < 6; ++k) {
    ASSERT_TRUE(source.Next(&frame));
    EXPECT_EQ(frame.dropped, k < 3) << "frame " << k;
    if (!frame.dropped) { EXPECT_EQ(frame.images[1].at<cv::Vec3b>(0, 0)[0], k - 3) << "frame " << k; }
  }
  EXPECT_EQ(source.unpaired(), 3);
}

TEST(VideoFrameSource, RefusesCamerasThatDoNotFitTheirImages) {
  std::vector<std::unique_ptr<ImageSource>> sources;
  sources.push_back(std::make_unique<ScriptedSource>(std::vector<double>{0.0}, 10, 32, 24));
  try {
    VideoFrameSource source(std::move(sources), {CameraOf(64, 48)}, {});
    FAIL() << "a 32x24 source with a 64x48 camera was taken";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("32x24"), std::string::npos) << e.what();
  }
  std::vector<std::unique_ptr<ImageSource>> two;
  two.push_back(std::make_unique<ScriptedSource>(std::vector<double>{0.0}, 10));
  VideoFrameSourceOptions options;
  options.backgrounds = {"a.png", "b.png"};  // one camera, two backgrounds
  EXPECT_THROW(VideoFrameSource(std::move(two), {CameraOf(32, 24)}, options), InputError);
}

TEST(VideoFrameSource, StopsAtMaxFrames) {
  std::vector<std::unique_ptr<ImageSource>> sources;
  sources.push_back(std::make_unique<ScriptedSource>(std::vector<double>{0.0, 0.1, 0.2, 0.3}, 10));
  VideoFrameSourceOptions options;
  options.max_frames = 2;
  VideoFrameSource source(std::move(sources), {CameraOf(32, 24)}, options);
  EXPECT_EQ(source.NumFrames(), 2);
  Frame frame;
  EXPECT_TRUE(source.Next(&frame));
  EXPECT_TRUE(source.Next(&frame));
  EXPECT_FALSE(source.Next(&frame));
}

// A 1280x720 scene (a fixed random texture) with a person-sized bright block 400 px tall
// walking across it, 12 px a frame, 60 frames.
class WalkerSource : public ImageSource {
 public:
  static constexpr int kWidth = 1280, kHeight = 720, kFrames = 60, kTall = 400, kWide = 120;
  WalkerSource() : scene_(kHeight, kWidth, CV_8UC3) {
    cv::randu(scene_, cv::Scalar::all(40), cv::Scalar::all(120));
    cv::GaussianBlur(scene_, scene_, cv::Size(7, 7), 0);
  }
  const std::string& name() const override { return name_; }
  int width() const override { return kWidth; }
  int height() const override { return kHeight; }
  double fps() const override { return 30; }
  int NumFrames() const override { return kFrames; }
  static cv::Rect Body(int k) { return cv::Rect(200 + 12 * k, 220, kWide, kTall); }
  cv::Mat At(int k) const {
    cv::Mat image = scene_.clone();
    image(Body(k)).setTo(cv::Scalar(230, 200, 180));
    return image;
  }
  bool Read(Image* image) override {
    if (next_ >= kFrames) return false;
    image->bgr = At(next_);
    image->time_s = next_ / 30.0;
    image->index = next_++;
    return true;
  }
  std::vector<cv::Mat> Sample(int n) override {
    std::vector<cv::Mat> images;
    for (int i = 0; i < n && i < kFrames; ++i) images.push_back(At(i * kFrames / std::min(n, kFrames)));
    return images;
  }

 private:
  std::string name_ = "walker";
  cv::Mat scene_;
  int next_ = 0;
};

double Iou(const cv::Mat& a, const cv::Mat& b) {
  return static_cast<double>(cv::countNonZero(a & b)) / std::max(1, cv::countNonZero(a | b));
}

// A learnt background's masks made at the working resolution: the person brought to
// about person_px tall (the scale from the moving regions of the learning images), the
// images handed on at full size, the mask the walker's (against the block drawn at that
// size), and the working-resolution source on top keeping that size rather than scaling
// again. With person_px 0, full size.
TEST(VideoFrameSource, MakesALearntBackgroundsMasksAtTheWorkingResolution) {
  const Camera camera = CameraOf(WalkerSource::kWidth, WalkerSource::kHeight);
  for (const double person_px : {0.0, 200.0}) {
    SCOPED_TRACE(person_px);
    std::vector<std::unique_ptr<ImageSource>> sources;
    sources.push_back(std::make_unique<WalkerSource>());
    VideoFrameSourceOptions options;
    options.person_px = person_px;
    auto inner = std::make_unique<VideoFrameSource>(std::move(sources), std::vector<Camera>{camera}, options);
    const VideoFrameSource* video = inner.get();
    WorkingResolutionSource source(std::move(inner), {}, false);
    const double s = video->mask_scale(0);
    if (person_px == 0) {
      EXPECT_EQ(s, 1.0);
    } else {
      EXPECT_NEAR(s * WalkerSource::kTall, person_px, 0.1 * person_px);
    }
    // What the tracker sees: the masks' size and camera, scaled by the same s (once).
    EXPECT_NEAR(source.scales()[0], s * (person_px == 0 ? 200.0 / WalkerSource::kTall : 1.0), 0.02);
    const Camera& seen = source.cameras()[0];
    Frame frame;
    double worst = 1;
    for (int k = 0; source.Next(&frame); ++k) {
      ASSERT_EQ(frame.images[0].size(), cv::Size(WalkerSource::kWidth, WalkerSource::kHeight));
      ASSERT_EQ(frame.masks[0].size(), cv::Size(seen.width, seen.height));
      if (k < 5) continue;  // MOG2 settles
      cv::Mat truth = cv::Mat::zeros(WalkerSource::kHeight, WalkerSource::kWidth, CV_8UC1);
      truth(WalkerSource::Body(k)).setTo(255);
      worst = std::min(worst, Iou(frame.masks[0], ScaleMask(truth, frame.masks[0].size())));
    }
    EXPECT_GT(worst, 0.9);
  }
}

}  // namespace
}  // namespace jgpm
