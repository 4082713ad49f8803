// A synthetic clip must be what it claims: its ground truth is the trial's forward
// kinematics at the sampled frames, its cameras are the ones the images were rendered
// through (joints land inside the masks, the walker stays in view), and each degradation
// does what it says and nothing else.
#include "tracker/synthetic_clip.h"

#include <cmath>
#include <fstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>

#include "io/amc.h"
#include "io/asf.h"
#include "io/json_file.h"
#include "io/kinematics.h"
#include "test_support.h"

namespace jgpm {
namespace {

namespace fs = std::filesystem;

struct Trial {
  Skeleton skeleton;
  Motion motion;
  ClipSource source;
};
const Trial& Walk() {
  static const Trial trial = [] {
    Trial t;
    t.source = {(test::CmuRoot() / "subjects/07/07.asf").string(), (test::CmuRoot() / "subjects/07/07_02.amc").string()};
    t.skeleton = ReadAsf(t.source.asf);
    t.motion = ReadAmc(t.source.amc, t.skeleton);
    return t;
  }();
  return trial;
}

ClipOptions SmallClip() {
  ClipOptions options;
  options.rig.width = 160;
  options.rig.height = 120;
  options.max_frames = 0;
  return options;
}

// Every frame of a video.
std::vector<cv::Mat> ReadVideo(const fs::path& path) {
  cv::VideoCapture video(path.string());
  std::vector<cv::Mat> frames;
  for (cv::Mat frame; video.read(frame);) frames.push_back(frame.clone());
  return frames;
}

TEST(SyntheticClipTest, GroundTruthCamerasAndMasksAgree) {
  const Trial& walk = Walk();
  test::TempDir dir;
  ClipOptions options = SmallClip();
  options.rig.num_cameras = 3;
  const ClipSummary summary = RenderClip(walk.skeleton, walk.motion, walk.source, {}, options,
                                         (dir.path() / "clip").string());
  std::printf("%s\n", summary.BriefReport().c_str());
  // 07_02: 329 frames at 120 fps -> frames 0, 4, ..., 328 at 30 fps.
  EXPECT_EQ(summary.frames, 83);
  EXPECT_EQ(summary.dropped, 0);
  const fs::path clip = dir.path() / "clip";
  EXPECT_FALSE(fs::exists(dir.path() / "clip.partial"));
  const nlohmann::json truth = ReadJsonFile(clip / "ground_truth.json", "ground truth");
  ASSERT_EQ(truth["frames"].size(), 83u);
  EXPECT_EQ(truth["fps"], 30.0);
  ASSERT_EQ(truth["cameras"].size(), 3u);
  const Kinematics kinematics(walk.skeleton);
  for (int k = 0; k < 83; ++k) {
    const nlohmann::json& f = truth["frames"][k];
    ASSERT_EQ(f["source_frame"], 4 * k);
    EXPECT_DOUBLE_EQ(f["time_s"].get<double>(), k / 30.0);
    const Eigen::Matrix3Xd joints = kinematics.Compute(walk.motion.Frame(4 * k));
    ASSERT_EQ(f["joints_mm"].size(), static_cast<size_t>(joints.cols()));
    for (int j = 0; j < joints.cols(); ++j)
      for (int d = 0; d < 3; ++d) ASSERT_NEAR(f["joints_mm"][j][d].get<double>(), joints(d, j), 0.006);
  }
  for (size_t c = 0; c < 3; ++c) {
    const Camera camera = ReadCameraYaml((clip / ("cam" + std::to_string(c) + ".yaml")).string()).camera;
    EXPECT_NEAR(camera.fx, truth["cameras"][c]["fx"].get<double>(), 1e-9);
    EXPECT_TRUE(camera.cam_from_world_rotation.isApprox(summary.cameras[c].cam_from_world_rotation, 1e-12));
    const std::vector<cv::Mat> video = ReadVideo(clip / (camera.name + ".avi"));
    ASSERT_EQ(video.size(), 83u);
    EXPECT_EQ(video.back().size(), cv::Size(160, 120));
    for (int k = 0; k < 83; k += 10) {
      const cv::Mat mask = cv::imread((clip / "masks" / camera.name / cv::format("%06d.png", k)).string(), cv::IMREAD_UNCHANGED);
      ASSERT_EQ(mask.size(), cv::Size(160, 120));
      // The walker stays in view: nothing touches the border, every joint is inside.
      EXPECT_EQ(cv::countNonZero(mask.row(0)) + cv::countNonZero(mask.row(119)) +
                    cv::countNonZero(mask.col(0)) + cv::countNonZero(mask.col(159)), 0);
      // (Within a pixel: at this size a finger is under a pixel wide.)
      cv::Mat grown;
      cv::dilate(mask, grown, cv::Mat());
      const Eigen::Matrix3Xd joints = kinematics.Compute(walk.motion.Frame(4 * k));
      for (int j = 0; j < joints.cols(); ++j) {
        Eigen::Vector2d p;
        ASSERT_TRUE(camera.Project(joints.col(j), &p));
        EXPECT_EQ(grown.at<uint8_t>(static_cast<int>(std::lround(p.y())), static_cast<int>(std::lround(p.x()))), 255)
            << camera.name << " frame " << k << " " << walk.skeleton.bones[j].name;
      }
      // Without degradations the observed masks are the exact ones.
      const cv::Mat observed = cv::imread((clip / "observed" / camera.name / cv::format("%06d.png", k)).string(), cv::IMREAD_UNCHANGED);
      EXPECT_EQ(cv::countNonZero(observed != mask), 0);
    }
  }
  EXPECT_TRUE(fs::exists(clip / "contact_sheet.png"));
}

TEST(SyntheticClipTest, VideoShowsTheWalkerOverAStaticRoom) {
  const Trial& walk = Walk();
  test::TempDir dir;
  ClipOptions options = SmallClip();
  options.rig.num_cameras = 1;
  options.max_frames = 20;
  RenderClip(walk.skeleton, walk.motion, walk.source, {}, options, (dir.path() / "clip").string());
  const std::vector<cv::Mat> video = ReadVideo(dir.path() / "clip/cam0.avi");
  ASSERT_EQ(video.size(), 20u);
  const cv::Mat& first = video.front();
  const cv::Mat& last = video.back();
  const cv::Mat mask0 = cv::imread((dir.path() / "clip/masks/cam0/000000.png").string(), cv::IMREAD_GRAYSCALE);
  const cv::Mat mask19 = cv::imread((dir.path() / "clip/masks/cam0/000019.png").string(), cv::IMREAD_GRAYSCALE);
  cv::Mat diff;
  cv::absdiff(first, last, diff);
  cv::cvtColor(diff, diff, cv::COLOR_BGR2GRAY);
  // Where neither frame has the walker, only noise and compression differ; where one has
  // him, the picture changes.
  const cv::Mat background = (mask0 == 0) & (mask19 == 0), walker = mask0 ^ mask19;
  const double still = cv::mean(diff, background)[0], moved = cv::mean(diff, walker)[0];
  std::printf("frame 0 vs 19: mean change %.1f grey levels in the room, %.1f where the walker moved\n", still, moved);
  EXPECT_LT(still, 6);
  EXPECT_GT(moved, 25);
}

TEST(SyntheticClipTest, DegradationsDoWhatTheySay) {
  const Trial& walk = Walk();
  test::TempDir dir;
  ClipOptions options = SmallClip();
  options.rig.num_cameras = 1;
  options.max_frames = 40;
  options.degradations.drop_rate = 0.25;
  options.degradations.mask_noise_px = 1;  // limbs are 3-4 px wide at 160x120
  options.degradations.holes = 4;
  options.degradations.clutter_blobs = 3;
  options.degradations.lighting_gain = 0.5;
  options.degradations.sensor_noise = 0;
  const ClipSummary summary = RenderClip(walk.skeleton, walk.motion, walk.source, {}, options,
                                         (dir.path() / "clip").string());
  const fs::path clip = dir.path() / "clip";
  EXPECT_GT(summary.dropped, 3);
  EXPECT_LT(summary.dropped, 20);
  const nlohmann::json truth = ReadJsonFile(clip / "ground_truth.json", "ground truth");
  int kept = 0, differing = 0, clutter_outside = 0;
  for (int k = 0; k < 40; ++k) {
    const nlohmann::json& f = truth["frames"][k];
    const fs::path mask_path = clip / "masks/cam0" / cv::format("%06d.png", k);
    ASSERT_EQ(f["dropped"].get<bool>(), !fs::exists(mask_path)) << k;
    if (f["dropped"].get<bool>()) {
      EXPECT_TRUE(f["video_frame"].is_null());
      continue;
    }
    EXPECT_EQ(f["video_frame"], kept++);
    const cv::Mat exact = cv::imread(mask_path.string(), cv::IMREAD_GRAYSCALE);
    const cv::Mat observed = cv::imread((clip / "observed/cam0" / cv::format("%06d.png", k)).string(), cv::IMREAD_GRAYSCALE);
    const double iou = static_cast<double>(cv::countNonZero(exact & observed)) / cv::countNonZero(exact | observed);
    differing += iou < 0.999;
    EXPECT_GT(cv::countNonZero(exact & observed), 0.4 * cv::countNonZero(exact)) << k;
    // Clutter: foreground far from the walker.
    cv::Mat near;
    cv::dilate(exact, near, cv::Mat(), cv::Point(-1, -1), 5);
    clutter_outside += cv::countNonZero(observed & ~near) > 20;
  }
  EXPECT_EQ(kept, 40 - summary.dropped);
  EXPECT_GT(differing, kept / 2);
  EXPECT_GT(clutter_outside, kept / 2);
  const std::vector<cv::Mat> video = ReadVideo(clip / "cam0.avi");
  ASSERT_EQ(static_cast<int>(video.size()), kept);
  // Lighting: the last frame is half as bright as the first outside the walker and blobs.
  const double ratio = cv::mean(video.back())[1] / cv::mean(video.front())[1];
  std::printf("brightness last/first frame: %.3f (gain 0.5)\n", ratio);
  EXPECT_NEAR(ratio, 0.5, 0.06);
}

TEST(SyntheticClipTest, SameSeedSameClip) {
  const Trial& walk = Walk();
  test::TempDir dir;
  ClipOptions options = SmallClip();
  options.rig.num_cameras = 1;
  options.max_frames = 8;
  options.degradations.holes = 3;
  options.degradations.drop_rate = 0.3;
  for (const char* name : {"a", "b"})
    RenderClip(walk.skeleton, walk.motion, walk.source, {}, options, (dir.path() / name).string());
  const nlohmann::json a = ReadJsonFile(dir.path() / "a/ground_truth.json", "a");
  const nlohmann::json b = ReadJsonFile(dir.path() / "b/ground_truth.json", "b");
  EXPECT_EQ(a, b);
  for (int k = 0; k < 8; ++k) {
    const fs::path pa = dir.path() / "a/observed/cam0" / cv::format("%06d.png", k);
    if (!fs::exists(pa)) continue;
    const cv::Mat ma = cv::imread(pa.string(), cv::IMREAD_GRAYSCALE);
    const cv::Mat mb = cv::imread((dir.path() / "b/observed/cam0" / cv::format("%06d.png", k)).string(), cv::IMREAD_GRAYSCALE);
    EXPECT_EQ(cv::countNonZero(ma != mb), 0);
  }
}

TEST(SyntheticClipTest, BadRequestsLeaveNothingBehind) {
  const Trial& walk = Walk();
  test::TempDir dir;
  const fs::path taken = dir.path() / "taken";
  fs::create_directories(taken);
  dir.Write("taken/keep.txt", "mine");
  test::ExpectInputError([&] { RenderClip(walk.skeleton, walk.motion, walk.source, {}, SmallClip(), taken.string()); },
                         {"taken", "not empty"});
  EXPECT_TRUE(fs::exists(taken / "keep.txt"));
  ClipOptions options = SmallClip();
  options.fps = 240;
  test::ExpectInputError([&] { RenderClip(walk.skeleton, walk.motion, walk.source, {}, options, (dir.path() / "x").string()); },
                         {"fps 240", "exceeds"});
  options = SmallClip();
  options.degradations.drop_rate = 1;
  test::ExpectInputError([&] { RenderClip(walk.skeleton, walk.motion, walk.source, {}, options, (dir.path() / "x").string()); },
                         {"drop rate"});
  Camera bad = LookAtCamera("c", 160, 120, 100, {0, 1500, -4000}, {0, 1000, 0});
  bad.fx = -1;
  test::ExpectInputError([&] { RenderClip(walk.skeleton, walk.motion, walk.source, {bad}, SmallClip(), (dir.path() / "x").string()); },
                         {"camera c", "focal"});
  bad = LookAtCamera("sub/dir", 160, 120, 100, {0, 1500, -4000}, {0, 1000, 0});
  test::ExpectInputError([&] { RenderClip(walk.skeleton, walk.motion, walk.source, {bad}, SmallClip(), (dir.path() / "x").string()); },
                         {"sub/dir", "camera name"});
  // A failure half way (here: the progress callback throws) leaves no half clip.
  options = SmallClip();
  options.max_frames = 10;
  EXPECT_THROW(RenderClip(walk.skeleton, walk.motion, walk.source, {}, options, (dir.path() / "x").string(),
                          [](int done, int) { if (done == 5) throw std::runtime_error("stop"); }),
               std::runtime_error);
  EXPECT_FALSE(fs::exists(dir.path() / "x"));
  EXPECT_FALSE(fs::exists(dir.path() / "x.partial"));
}

TEST(SyntheticClipTest, GivenCamerasAreUsedAsTheyAre) {
  const Trial& walk = Walk();
  test::TempDir dir;
  Camera camera = LookAtCamera("left", 200, 150, 120, {-5000, 1600, 0}, {0, 900, 0});
  camera.distortion = {-0.1, 0.01, 0, 0, 0};
  ClipOptions options = SmallClip();
  options.max_frames = 3;
  const ClipSummary summary = RenderClip(walk.skeleton, walk.motion, walk.source, {camera}, options,
                                         (dir.path() / "clip/").string());
  ASSERT_EQ(summary.cameras.size(), 1u);
  const CameraFile file = ReadCameraYaml((dir.path() / "clip/left.yaml").string());
  EXPECT_TRUE(file.has_extrinsics);
  EXPECT_EQ(file.camera.distortion, camera.distortion);
  EXPECT_EQ(cv::imread((dir.path() / "clip/masks/left/000002.png").string()).size(), cv::Size(200, 150));
}

}  // namespace
}  // namespace jgpm
