// Painted static occluders against hand-made answers: a painting is read as it was painted
// (any colour channel; an alpha channel is not paint), refused with the file named when it
// is not the camera's size, and handed to every frame as its hidden pixels at the masks'
// size, a pixel hidden when the painting covers any part of it; the factory gives one
// painting per camera or refuses.
#include "tracker/frames/occluder_masks.h"

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "tests/test_support.h"
#include "tracker/clip/clip_format.h"
#include "tracker/frames/frame_source_factory.h"
#include "tracker/frames/working_resolution.h"

namespace jgpm {
namespace {

Camera Cam(const std::string& name, int width, int height) {
  return LookAtCamera(name, width, height, 0.8 * width, Eigen::Vector3d(0, 1500, -4000), Eigen::Vector3d(0, 900, 0));
}

// Frames of one camera whose masks are `size` (a source that made them smaller).
class Masks : public FrameSource {
 public:
  Masks(const Camera& camera, cv::Size size) : cameras_{camera}, size_(size) {}
  const std::vector<Camera>& cameras() const override { return cameras_; }
  double fps() const override { return 30; }
  int NumFrames() const override { return 3; }
  bool Next(Frame* frame) override {
    if (next_ == 3) return false;
    *frame = Frame();
    frame->index = next_;
    frame->dropped = next_ == 1;
    if (!frame->dropped) frame->masks = {cv::Mat(size_, CV_8UC1, cv::Scalar(255))};
    ++next_;
    return true;
  }

 private:
  std::vector<Camera> cameras_;
  cv::Size size_;
  int next_ = 0;
};

TEST(OccluderMasks, APaintingIsReadFromAnyChannelAndMustBeTheCamerasSize) {
  test::TempDir dir;
  cv::Mat colour(240, 320, CV_8UC3, cv::Scalar(0, 0, 0));
  colour(cv::Rect(10, 200, 100, 40)).setTo(cv::Scalar(0, 0, 90));  // red only: a table
  colour(cv::Rect(250, 50, 20, 190)).setTo(cv::Scalar(30, 0, 0));  // blue only: a pillar
  const std::string path = (dir.path() / "cam0.png").string();
  ASSERT_TRUE(cv::imwrite(path, colour));
  const cv::Mat painted = ReadOccluderMask(path, Cam("cam0", 320, 240));
  ASSERT_EQ(painted.type(), CV_8UC1);
  EXPECT_EQ(cv::countNonZero(painted), 100 * 40 + 20 * 190);
  EXPECT_EQ(painted.at<uchar>(220, 50), 255);
  EXPECT_EQ(painted.at<uchar>(100, 260), 255);
  EXPECT_EQ(painted.at<uchar>(100, 100), 0);
  test::ExpectInputError([&] { ReadOccluderMask(path, Cam("cam0", 640, 480)); }, {path, "320x240", "640x480"});
  // Exported with an alpha channel: opaque black is unpainted, and so is a transparent
  // pixel whatever colour it keeps (it was all painted: alpha read as a colour).
  cv::Mat bgra(240, 320, CV_8UC4, cv::Scalar(0, 0, 0, 255));
  bgra(cv::Rect(10, 200, 100, 40)).setTo(cv::Scalar(0, 0, 90, 255));
  bgra(cv::Rect(200, 0, 50, 50)).setTo(cv::Scalar(40, 40, 40, 0));
  const std::string with_alpha = (dir.path() / "alpha.png").string();
  ASSERT_TRUE(cv::imwrite(with_alpha, bgra));
  const cv::Mat from_alpha = ReadOccluderMask(with_alpha, Cam("cam0", 320, 240));
  EXPECT_EQ(cv::countNonZero(from_alpha), 100 * 40);
  EXPECT_EQ(from_alpha.at<uchar>(220, 50), 255);
  const std::string text = dir.Write("not.png", "no image").string();
  test::ExpectInputError([&] { ReadOccluderMask(text, Cam("cam0", 320, 240)); }, {text, "PNG"});
}

TEST(OccluderMasks, EveryFrameHidesThePaintingAtItsMasksSize) {
  const Camera camera = Cam("cam0", 320, 240);
  cv::Mat painting(240, 320, CV_8UC1, cv::Scalar(0));
  painting(cv::Rect(11, 101, 40, 20)).setTo(255);  // odd corner: half-pixel edges at half size
  for (const cv::Size size : {cv::Size(320, 240), cv::Size(160, 120)}) {
    SCOPED_TRACE(size.width);
    OccludedSource source(std::make_unique<Masks>(camera, size), {painting});
    Frame frame;
    for (int k = 0; k < 3; ++k) {
      ASSERT_TRUE(source.Next(&frame));
      if (frame.dropped) {
        EXPECT_TRUE(frame.hidden.empty());
        continue;
      }
      ASSERT_EQ(frame.hidden.size(), 1u);
      ASSERT_EQ(frame.hidden[0].size(), size);
      // Brute force: a pixel is hidden when any full-size pixel under it is painted.
      const int f = 320 / size.width;
      for (int v = 0; v < size.height; ++v)
        for (int u = 0; u < size.width; ++u) {
          const bool any = cv::countNonZero(painting(cv::Rect(u * f, v * f, f, f))) > 0;
          ASSERT_EQ(frame.hidden[0].at<uchar>(v, u) != 0, any) << u << "," << v;
        }
      frame.hidden[0].setTo(0);  // the frame's own: the next frame's is whole again
    }
    EXPECT_FALSE(source.Next(&frame));
  }
}

TEST(OccluderPaintings, OnePerCameraOrAClipsOwn) {
  test::TempDir dir;
  const std::vector<Camera> cameras = {Cam("cam0", 320, 240), Cam("cam1", 320, 240)};
  cv::Mat painting(240, 320, CV_8UC1, cv::Scalar(0));
  painting(cv::Rect(0, 200, 320, 40)).setTo(255);
  const std::string path = (dir.path() / "p.png").string();
  ASSERT_TRUE(cv::imwrite(path, painting));
  FrameSourceSpec video;
  video.videos = {"a.avi", "b.avi"};
  EXPECT_TRUE(OccluderPaintings(video, cameras).empty());  // none given: none
  video.occluders = {path};
  test::ExpectInputError([&] { OccluderPaintings(video, cameras); }, {"--occluders", "1 paintings for 2 cameras"});
  video.occluders = {path, path};
  ASSERT_EQ(OccluderPaintings(video, cameras).size(), 2u);
  EXPECT_EQ(cv::countNonZero(OccluderPaintings(video, cameras)[1]), 320 * 40);

  // A clip's own: occluders/CAMERA.png where it has one, unless left out.
  FrameSourceSpec clip;
  clip.clip = dir.path().string();
  EXPECT_TRUE(OccluderPaintings(clip, cameras).empty());
  const ClipPaths paths{dir.path()};
  std::filesystem::create_directories(paths.Occluders("cam1").parent_path());
  ASSERT_TRUE(cv::imwrite(paths.Occluders("cam1").string(), painting));
  const std::vector<cv::Mat> own = OccluderPaintings(clip, cameras);
  ASSERT_EQ(own.size(), 2u);
  EXPECT_TRUE(own[0].empty());
  EXPECT_EQ(cv::countNonZero(own[1]), 320 * 40);
  clip.clip_occluders = false;
  EXPECT_TRUE(OccluderPaintings(clip, cameras).empty());
  clip.occluders = {path, path};
  test::ExpectInputError([&] { OccluderPaintings(clip, cameras); }, {"--occluders", "clip"});
}

}  // namespace
}  // namespace jgpm
