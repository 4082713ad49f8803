// The overlay videos written on their own thread against what was handed in: one video
// frame per tracked frame in order, a dropped frame shown as the last image dimmed, the
// body drawn where the camera that rendered it projects it, what AddAndDraw shows being
// what is written, a found light's shadow outlined on the floor, and an unwritable folder
// refused with the file named.
#include "tracker/run/overlay_videos.h"

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "io/mocap/asf.h"
#include "io/mocap/kinematics.h"
#include "test_support.h"

namespace jgpm {
namespace {

namespace fs = std::filesystem;

struct Scene {
  Skeleton skeleton = ReadAsf(test::CmuRoot() / "subjects/07/07.asf");
  BodyModel body{skeleton, {}, "07.asf"};
  Camera camera = LookAtCamera("cam0", 160, 120, 120, Eigen::Vector3d(0, 1000, -5000), Eigen::Vector3d(0, 900, 0));
  // Frame k: a grey image of brightness 40 + 20 k; dropped when k == 3.
  Frame MakeFrame(int k) const {
    Frame frame;
    frame.index = k;
    frame.dropped = k == 3;
    if (!frame.dropped) frame.images = {cv::Mat(camera.height, camera.width, CV_8UC3, cv::Scalar::all(40 + 20 * k))};
    return frame;
  }
  // Lost (nothing drawn) except frame 5: the rest pose standing at the origin.
  TrackedFrame Estimate(int k) const {
    TrackedFrame f;
    f.index = k;
    if (k == 5) {
      f.status = TrackStatus::kTracked;
      f.state = Eigen::VectorXd::Zero(3);
      f.joints_mm = Kinematics(skeleton).Compute(std::vector<double>(skeleton.NumChannels(), 0.0).data());
      f.joints_mm.row(1).array() -= f.joints_mm.row(1).minCoeff();  // feet on the floor
    }
    return f;
  }
};

std::vector<cv::Mat> ReadVideo(const fs::path& path) {
  cv::VideoCapture video(path.string());
  std::vector<cv::Mat> frames;
  cv::Mat frame;
  while (video.read(frame)) frames.push_back(frame.clone());
  return frames;
}

double Brightness(const cv::Mat& image, const cv::Rect& box) { return cv::mean(image(box))[0]; }

TEST(OverlayVideos, WritesEveryFrameInOrderAndDimsADroppedOne) {
  const Scene scene;
  const test::TempDir temp;
  const fs::path& dir = temp.path();
  std::vector<cv::Mat> shown5;
  {
    OverlayVideos videos(dir, {scene.camera}, 25, scene.body, scene.skeleton, 2);
    for (int k = 0; k < 7; ++k) {
      if (k == 5) {
        shown5 = videos.AddAndDraw(scene.MakeFrame(k), scene.Estimate(k));
      } else {
        videos.Add(scene.MakeFrame(k), scene.Estimate(k));
      }
    }
    videos.Close();
  }
  const std::vector<cv::Mat> frames = ReadVideo(dir / "overlay_cam0.avi");
  ASSERT_EQ(frames.size(), 7u);
  // A corner away from the status line and the body: the image's own brightness.
  const cv::Rect corner(130, 90, 20, 20);
  for (int k : {0, 1, 2, 4, 6}) EXPECT_NEAR(Brightness(frames[k], corner), 40 + 20 * k, 3) << k;
  EXPECT_NEAR(Brightness(frames[3], corner), 0.5 * (40 + 20 * 2), 3);  // frame 2's, dimmed
  // Frame 5 has the body drawn over its middle, where the camera projects the hips.
  ASSERT_EQ(shown5.size(), 1u);
  Eigen::Vector2d hips;
  ASSERT_TRUE(scene.camera.Project(Eigen::Vector3d(0, 950, 0), &hips));
  const cv::Rect middle(static_cast<int>(hips.x()) - 15, static_cast<int>(hips.y()) - 30, 30, 60);
  cv::Mat difference;
  cv::absdiff(shown5[0](middle), cv::Scalar::all(140), difference);
  EXPECT_GT(cv::countNonZero(difference.reshape(1) > 40), 20);  // lines over the plain grey
  cv::absdiff(frames[5], shown5[0], difference);
  EXPECT_LT(cv::mean(difference)[0], 4);  // what was shown is what was written (MJPG's loss)
}

// With the light of the walkers' shadows found, the body's shadow is outlined on the
// floor: around where the camera projects the head's shadow (the head's top carried along
// the light onto the floor, by hand), and nothing there without the light.
TEST(OverlayVideos, AFoundLightsShadowIsOutlinedOnTheFloor) {
  const Scene scene;
  const test::TempDir temp;
  TrackedFrame estimate = scene.Estimate(5);
  const Eigen::Vector3d light = Eigen::Vector3d(1, 1, 0).normalized();  // 45 degrees up, from +x
  const Eigen::Index top = [&] {
    Eigen::Index j;
    estimate.joints_mm.row(1).maxCoeff(&j);
    return j;
  }();
  const Eigen::Vector3d head = estimate.joints_mm.col(top);
  const Eigen::Vector3d on_floor = head - head.y() / light.y() * light;
  Eigen::Vector2d pixel;
  ASSERT_TRUE(scene.camera.Project(on_floor, &pixel));
  const cv::Rect around(static_cast<int>(pixel.x()) - 6, static_cast<int>(pixel.y()) - 6, 13, 13);
  ASSERT_TRUE((cv::Rect(0, 0, scene.camera.width, scene.camera.height) & around) == around);
  const auto drawn = [&](const std::optional<Eigen::Vector3d>& found) {
    estimate.shadow_light = found;
    OverlayVideos videos(temp.path(), {scene.camera}, 25, scene.body, scene.skeleton);
    const cv::Mat shown = videos.AddAndDraw(scene.MakeFrame(5), estimate).at(0);
    videos.Close();
    cv::Mat difference;
    cv::absdiff(shown(around), cv::Scalar::all(140), difference);
    return cv::countNonZero(difference.reshape(1) > 40);
  };
  EXPECT_EQ(drawn(std::nullopt), 0);
  EXPECT_GT(drawn(light), 6);
}

TEST(OverlayVideos, AnUnwritableFolderIsNamed) {
  const Scene scene;
  const test::TempDir temp;
  test::ExpectInputError(
      [&] { OverlayVideos videos(temp.path() / "no" / "such", {scene.camera}, 25, scene.body, scene.skeleton); },
      {"overlay_cam0.avi", "cannot write"});
}

}  // namespace
}  // namespace jgpm
