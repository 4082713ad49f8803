// The working resolution against hand-computed answers: a scaled camera sees a point
// where the scaled image has it, a mask's rectangle scales to the rectangle, and the
// source reads ahead, chooses each camera's scale from its tallest blob, and hands every
// frame on in order.
#include "tracker/frames/working_resolution.h"

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

namespace jgpm {
namespace {

TEST(ScaleCamera, SeesAPointWhereTheScaledImageHasIt) {
  const Camera camera = LookAtCamera("cam0", 1280, 720, 900, Eigen::Vector3d(0, 1500, -4000), Eigen::Vector3d(300, 900, 0));
  const Camera half = ScaleCamera(camera, 0.5);
  EXPECT_EQ(half.width, 640);
  EXPECT_EQ(half.height, 360);
  for (const Eigen::Vector3d& p : {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(400, 1700, 300), Eigen::Vector3d(-900, 100, 800)}) {
    Eigen::Vector2d full, scaled;
    ASSERT_TRUE(camera.Project(p, &full));
    ASSERT_TRUE(half.Project(p, &scaled));
    // Pixel k covers [k - 0.5, k + 0.5]: the scaled image's coordinate of the same place.
    EXPECT_NEAR(scaled.x(), (full.x() + 0.5) * 0.5 - 0.5, 1e-9);
    EXPECT_NEAR(scaled.y(), (full.y() + 0.5) * 0.5 - 0.5, 1e-9);
  }
}

TEST(ScaleMask, ARectangleStaysTheRectangle) {
  cv::Mat mask(120, 160, CV_8UC1, cv::Scalar(0));
  mask(cv::Rect(40, 20, 30, 60)).setTo(255);
  const cv::Mat half = ScaleMask(mask, cv::Size(80, 60));
  ASSERT_EQ(half.type(), CV_8UC1);
  EXPECT_EQ(cv::countNonZero(half), 15 * 30);
  EXPECT_EQ(cv::boundingRect(half), cv::Rect(20, 10, 15, 30));
  EXPECT_EQ(ScaleMask(mask, mask.size()).data, mask.data);  // the same size: untouched
}

// A source of `frames` frames of two cameras: in camera 0 a blob `tall` px tall (from
// frame `from` on), camera 1 empty.
class FakeSource : public FrameSource {
 public:
  FakeSource(int frames, int tall, int from) : frames_(frames), tall_(tall), from_(from) {
    cameras_ = {LookAtCamera("cam0", 640, 480, 500, Eigen::Vector3d(0, 1500, -4000), Eigen::Vector3d(0, 900, 0)),
                LookAtCamera("cam1", 320, 240, 250, Eigen::Vector3d(4000, 1500, 0), Eigen::Vector3d(0, 900, 0))};
  }
  const std::vector<Camera>& cameras() const override { return cameras_; }
  double fps() const override { return 30; }
  int NumFrames() const override { return frames_; }
  bool Next(Frame* frame) override {
    if (next_ == frames_) return false;
    frame->index = next_;
    frame->masks = {cv::Mat(480, 640, CV_8UC1, cv::Scalar(0)), cv::Mat(240, 320, CV_8UC1, cv::Scalar(0))};
    if (next_ >= from_) frame->masks[0](cv::Rect(300, 10, 40, tall_)).setTo(255);
    frame->images = {cv::Mat(480, 640, CV_8UC3, cv::Scalar(next_, 0, 0))};
    ++next_;
    return true;
  }

 private:
  std::vector<Camera> cameras_;
  int frames_, tall_, from_, next_ = 0;
};

TEST(WorkingResolutionSource, BringsATallPersonTo200PxAndHandsEveryFrameOn) {
  WorkingResolutionOptions options;
  WorkingResolutionSource source(std::make_unique<FakeSource>(50, 400, 10), options, false);
  ASSERT_EQ(source.scales().size(), 2u);
  EXPECT_DOUBLE_EQ(source.scales()[0], 0.5);  // 200 / 400
  EXPECT_DOUBLE_EQ(source.scales()[1], 1.0);  // nobody: as it is
  EXPECT_EQ(source.cameras()[0].width, 320);
  EXPECT_EQ(source.full_cameras()[0].width, 640);
  Frame frame;
  for (int k = 0; k < 50; ++k) {
    ASSERT_TRUE(source.Next(&frame)) << k;
    EXPECT_EQ(frame.index, k);
    ASSERT_EQ(frame.masks[0].size(), cv::Size(320, 240));
    EXPECT_EQ(frame.masks[1].size(), cv::Size(320, 240));
    EXPECT_EQ(frame.images[0].size(), cv::Size(640, 480));  // images as they came
    EXPECT_EQ(frame.images[0].at<cv::Vec3b>(0, 0)[0], k);
    EXPECT_EQ(cv::countNonZero(frame.masks[0]), k >= 10 ? 20 * 200 : 0);
  }
  EXPECT_FALSE(source.Next(&frame));
}

TEST(WorkingResolutionSource, LeavesSmallPeopleLiveCamerasAndTheFullResolutionAlone) {
  WorkingResolutionOptions options;
  EXPECT_DOUBLE_EQ(WorkingResolutionSource(std::make_unique<FakeSource>(50, 150, 0), options, false).scales()[0], 1.0);
  // Seen only after the lookahead: as it is.
  EXPECT_DOUBLE_EQ(WorkingResolutionSource(std::make_unique<FakeSource>(50, 400, 40), options, false).scales()[0], 1.0);
  EXPECT_DOUBLE_EQ(WorkingResolutionSource(std::make_unique<FakeSource>(50, 400, 0), options, true).scales()[0], 1.0);
  options.enabled = false;
  EXPECT_DOUBLE_EQ(WorkingResolutionSource(std::make_unique<FakeSource>(50, 400, 0), options, false).scales()[0], 1.0);
}

}  // namespace
}  // namespace jgpm
