// Several cameras' images paired into frames by time: the first camera sets the frames,
// each other camera gives its image within half a frame period, and a frame some camera
// did not see is handed out as dropped (predicted by the tracker), never as an empty view.
#include "tracker/frames/video_frame_source.h"

#include <gtest/gtest.h>

#include "io/base/error.h"

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

}  // namespace
}  // namespace jgpm
