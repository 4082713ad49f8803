// A synthetic clip must be what it claims: its ground truth is the trial's forward
// kinematics at the sampled frames, its cameras are the ones the images were rendered
// through (joints land inside the masks, the walker stays in view), and each degradation
// does what it says and nothing else.
#include "tracker/clip/synthetic_clip.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numbers>
#include <fstream>
#include <random>
#include <tuple>

#include <Eigen/Geometry>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>

#include "io/base/json_file.h"
#include "io/base/text_reader.h"
#include "io/mocap/amc.h"
#include "io/mocap/asf.h"
#include "io/mocap/kinematics.h"
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
  const ClipGroundTruth truth = ReadGroundTruth(clip / "ground_truth.json");
  ASSERT_EQ(truth.frames.size(), 83u);
  EXPECT_EQ(truth.fps, 30.0);
  ASSERT_EQ(truth.cameras.size(), 3u);
  const Kinematics kinematics(walk.skeleton);
  for (int k = 0; k < 83; ++k) {
    const ClipFrame& f = truth.frames[k];
    ASSERT_EQ(f.source_frame, 4 * k);
    EXPECT_DOUBLE_EQ(f.time_s, k / 30.0);
    EXPECT_EQ(f.video_frame, k);
    const Eigen::Matrix3Xd joints = kinematics.Compute(walk.motion.Frame(4 * k));
    ASSERT_EQ(f.joints_mm.cols(), joints.cols());
    ASSERT_LE((f.joints_mm - joints).cwiseAbs().maxCoeff(), 0.005 + 1e-9);  // written to 0.01 mm
  }
  for (size_t c = 0; c < 3; ++c) {
    const Camera camera = ReadCameraYaml((clip / ("cam" + std::to_string(c) + ".yaml")).string()).camera;
    EXPECT_NEAR(camera.fx, truth.cameras[c].fx, 1e-9);
    EXPECT_TRUE(camera.cam_from_world_rotation.isApprox(truth.cameras[c].cam_from_world_rotation, 1e-12));
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

// Each degradation, checked against what it promises: the observed mask is the exact one
// eroded or dilated by 0 or 1 px (the 3x3 ellipse), minus at most 4 holes of radius <= 5,
// plus clutter blobs; dropped frames have no image or video frame; the light ramps to
// the gain. A degradation that did more, less or something else fails one of these.
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
  const ClipPaths clip{dir.path() / "clip"};
  // 39 frames that may drop at 0.25: 9.75 expected, 3-17 covers 99.8% of draws.
  EXPECT_GE(summary.dropped, 3);
  EXPECT_LE(summary.dropped, 17);
  const ClipGroundTruth truth = ReadGroundTruth(clip.GroundTruth());
  const cv::Mat disc = cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(3, 3));
  constexpr int kHoleArea = 81;  // pixels of a filled circle of radius 5
  // The clutter as the renderer places it: camera 0's stream, one step per clip frame.
  std::mt19937_64 rng(options.seed * 1000003);
  MovingClutter blobs(3, 160, 120, &rng);
  cv::Mat clutter(120, 160, CV_8UC1);
  int kept = 0, eroded = 0, dilated = 0, unchanged = 0, holed = 0, cluttered = 0;
  for (int k = 0; k < 40; ++k) {
    blobs.Step();
    const ClipFrame& f = truth.frames[k];
    ASSERT_EQ(f.dropped, !fs::exists(clip.Mask("cam0", k))) << k;
    ASSERT_EQ(f.dropped, !fs::exists(clip.ObservedMask("cam0", k))) << k;
    if (f.dropped) {
      EXPECT_EQ(f.video_frame, -1);
      continue;
    }
    EXPECT_EQ(f.video_frame, kept++);
    blobs.Draw(&clutter);
    const cv::Mat exact = cv::imread(clip.Mask("cam0", k).string(), cv::IMREAD_GRAYSCALE);
    const cv::Mat observed = cv::imread(clip.ObservedMask("cam0", k).string(), cv::IMREAD_GRAYSCALE);
    EXPECT_EQ(cv::countNonZero(clutter & ~observed), 0) << "frame " << k << ": clutter missing from the mask";
    // Off the clutter, the observed mask is the exact one, eroded or dilated by <= 1 px,
    // less the holes: nothing added, at most 4 holes' worth removed.
    cv::Mat minus, plus;
    cv::erode(exact, minus, disc);
    cv::dilate(exact, plus, disc);
    const cv::Mat off_clutter = clutter == 0;
    int best = -1, best_missing = 1 << 30;
    const cv::Mat candidates[] = {exact, minus, plus};
    for (int i = 0; i < 3; ++i) {
      if (cv::countNonZero(observed & off_clutter & ~candidates[i]) > 0) continue;
      const int missing = cv::countNonZero(candidates[i] & off_clutter & ~observed);
      if (missing < best_missing) best = i, best_missing = missing;
    }
    ASSERT_GE(best, 0) << "frame " << k << ": the observed mask is no erosion or dilation by <= 1 px of the exact one";
    EXPECT_LE(best_missing, 4 * kHoleArea) << "frame " << k << ": more removed than 4 holes";
    (best == 0 ? unchanged : best == 1 ? eroded : dilated)++;
    holed += best_missing > 0;
    cluttered += cv::countNonZero(clutter & ~exact) > 20;
  }
  EXPECT_EQ(kept, 40 - summary.dropped);
  std::printf("%d kept frames: %d unchanged, %d eroded, %d dilated; %d holed, %d with clutter\n", kept, unchanged,
              eroded, dilated, holed, cluttered);
  EXPECT_GT(eroded, 0);
  EXPECT_GT(dilated, 0);
  EXPECT_GT(holed, kept * 3 / 4);
  EXPECT_GT(cluttered, kept / 2);
  const std::vector<cv::Mat> video = ReadVideo(clip.Video("cam0"));
  ASSERT_EQ(static_cast<int>(video.size()), kept);
  // Lighting: the last frame is half as bright as the first.
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

// A stop, by hand: the trial's time stands still at each pause for its length (pauses in
// any order), and the clip shows it: as many frames more as the pauses last, the pose held
// (same source frame, same joints) through each, and the trial going on from there.
TEST(SyntheticClipTest, APauseHoldsThePoseThenWalksOn) {
  const std::vector<ClipPause> pauses = {{1.0, 0.5}, {0.2, 0.3}};
  EXPECT_DOUBLE_EQ(TrialTime(0.1, pauses), 0.1);
  EXPECT_DOUBLE_EQ(TrialTime(0.35, pauses), 0.2);  // in the first stop
  EXPECT_DOUBLE_EQ(TrialTime(0.6, pauses), 0.3);
  EXPECT_DOUBLE_EQ(TrialTime(1.4, pauses), 1.0);   // in the second
  EXPECT_DOUBLE_EQ(TrialTime(1.9, pauses), 1.1);
  ClipPause pause;
  EXPECT_TRUE(ParsePause("0.5,1.25", &pause));
  EXPECT_EQ(pause.at_s, 0.5);
  EXPECT_EQ(pause.for_s, 1.25);
  for (const char* bad : {"", "1", "1,0", "-1,1", "1,61", "1,2,3", "1,2x", "nan,1", "1,nan"})
    EXPECT_FALSE(ParsePause(bad, &pause)) << bad;

  const Trial& walk = Walk();
  test::TempDir dir;
  ClipOptions options = SmallClip();
  options.rig.num_cameras = 1;
  options.contact_sheet = false;
  RenderClip(walk.skeleton, walk.motion, walk.source, {}, options, (dir.path() / "walk").string());
  options.pauses = {{0.5, 0.4}};
  RenderClip(walk.skeleton, walk.motion, walk.source, {}, options, (dir.path() / "stop").string());
  const ClipGroundTruth plain = ReadGroundTruth(dir.path() / "walk/ground_truth.json");
  const ClipGroundTruth stop = ReadGroundTruth(dir.path() / "stop/ground_truth.json");
  ASSERT_EQ(stop.frames.size(), plain.frames.size() + 12);  // 0.4 s at 30 frames a second
  for (size_t k = 0; k < stop.frames.size(); ++k) {
    const size_t shown = k < 15 ? k : k < 27 ? 15 : k - 12;  // the stop: frames 15-26 show frame 15
    EXPECT_EQ(stop.frames[k].source_frame, plain.frames[shown].source_frame) << k;
    EXPECT_TRUE(stop.frames[k].joints_mm.isApprox(plain.frames[shown].joints_mm, 1e-12)) << k;
  }

  ClipOptions late = options;
  late.pauses = {{60.0, 1.0}};  // after the trial's end
  test::ExpectInputError(
      [&] { RenderClip(walk.skeleton, walk.motion, walk.source, {}, late, (dir.path() / "late").string()); },
      {"--pause 60,1", "a stop must begin within it"});
  EXPECT_FALSE(fs::exists(dir.path() / "late"));
  late.pauses = {{1.0, 0.0}};
  std::string why;
  EXPECT_FALSE(late.Check(&why));
  EXPECT_NE(why.find("pause"), std::string::npos) << why;
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

// A given camera is used as it is, distortion included: the masks are where the camera's
// full lens model puts the joints, and measurably not where a pinhole camera would.
TEST(SyntheticClipTest, GivenCamerasAreUsedAsTheyAre) {
  const Trial& walk = Walk();
  test::TempDir dir;
  Camera camera = LookAtCamera("left", 200, 150, 150, {-4000, 1600, 0}, {0, 900, 0});
  camera.distortion = {-0.35, 0.12, 0.002, -0.001, 0};  // strong barrel
  Camera pinhole = camera;
  pinhole.distortion.assign(5, 0.0);
  ClipOptions options = SmallClip();
  options.max_frames = 12;
  const ClipSummary summary = RenderClip(walk.skeleton, walk.motion, walk.source, {camera}, options,
                                         (dir.path() / "clip/").string());
  ASSERT_EQ(summary.cameras.size(), 1u);
  const ClipPaths clip{dir.path() / "clip"};
  const CameraFile file = ReadCameraYaml(clip.CameraYaml("left").string());
  EXPECT_TRUE(file.has_extrinsics);
  EXPECT_EQ(file.camera.distortion, camera.distortion);
  const ClipGroundTruth truth = ReadGroundTruth(clip.GroundTruth());
  int inside = 0, inside_pinhole = 0, joints = 0;
  double shift = 0;
  for (int k = 0; k < 12; ++k) {
    const cv::Mat mask = cv::imread(clip.Mask("left", k).string(), cv::IMREAD_GRAYSCALE);
    ASSERT_EQ(mask.size(), cv::Size(200, 150));
    cv::Mat grown;
    cv::dilate(mask, grown, cv::Mat());
    const Eigen::Matrix3Xd& j = truth.frames[k].joints_mm;
    for (int b = 0; b < j.cols(); ++b) {
      Eigen::Vector2d p, q;
      ASSERT_TRUE(camera.Project(j.col(b), &p));
      ASSERT_TRUE(pinhole.Project(j.col(b), &q));
      auto in_mask = [&](const Eigen::Vector2d& x) {
        const int u = static_cast<int>(std::lround(x.x())), v = static_cast<int>(std::lround(x.y()));
        return u >= 0 && v >= 0 && u < 200 && v < 150 && grown.at<uint8_t>(v, u) == 255;
      };
      inside += in_mask(p);
      inside_pinhole += in_mask(q);
      shift += (p - q).norm();
      ++joints;
    }
  }
  std::printf("joints in the mask: %d of %d through the lens, %d as a pinhole; mean lens shift %.1f px\n", inside,
              joints, inside_pinhole, shift / joints);
  EXPECT_EQ(inside, joints);
  EXPECT_GT(shift / joints, 3.0);           // the lens matters here...
  EXPECT_LT(inside_pinhole, joints * 0.9);  // ...and a pinhole mask would miss joints
}

// An existing DIR.partial belongs to another render (or one that was stopped): it is
// refused, and kept as it was. It used to be removed.
TEST(SyntheticClipTest, AnotherRendersPartialFolderIsLeftAlone) {
  const Trial& walk = Walk();
  test::TempDir dir;
  fs::create_directories(dir.path() / "clip.partial");
  dir.Write("clip.partial/cam0.avi", "someone else's");
  ClipOptions options = SmallClip();
  options.max_frames = 2;
  test::ExpectInputError(
      [&] { RenderClip(walk.skeleton, walk.motion, walk.source, {}, options, (dir.path() / "clip").string()); },
      {"clip.partial", "another run"});
  EXPECT_EQ(ReadTextFile(dir.path() / "clip.partial/cam0.avi", "avi"), "someone else's");
  EXPECT_FALSE(fs::exists(dir.path() / "clip"));
}

// ground_truth.json reads back to what was written, and every malformed edit is refused
// naming the file and the field.
cv::Mat ReadMask(const fs::path& clip, const std::string& folder, const std::string& camera, int frame) {
  return cv::imread((clip / folder / camera / cv::format("%06d.png", frame)).string(), cv::IMREAD_GRAYSCALE);
}

// Occluders and passers hide the walker, nothing else changes him: with them, each exact
// mask is the same clip's mask without them minus what they cover, and they cover some.
// The shadow darkens the room in the video and is in the observed masks, never the exact.
TEST(SyntheticClipTest, OccludersHideTheWalkerAndTheShadowDarkensTheFloor) {
  const Trial& walk = Walk();
  test::TempDir dir;
  ClipOptions plain = SmallClip();
  plain.max_frames = 40;
  ClipOptions scene = plain;
  scene.scene.occluders = 3;
  scene.scene.shadow = true;
  RenderClip(walk.skeleton, walk.motion, walk.source, {}, plain, (dir.path() / "plain").string());
  RenderClip(walk.skeleton, walk.motion, walk.source, {}, scene, (dir.path() / "scene").string());
  const ClipGroundTruth truth = ReadGroundTruth(dir.path() / "scene/ground_truth.json");
  EXPECT_TRUE(truth.shadow);
  EXPECT_EQ(truth.occluders.size(), 3u);
  int hidden = 0, shadow_px = 0;
  double darker = 0;
  for (const char* camera : {"cam0", "cam1"}) {
    const cv::Mat room = cv::imread((dir.path() / "scene/background" / (std::string(camera) + ".png")).string());
    const std::vector<cv::Mat> video = ReadVideo(dir.path() / "scene" / (std::string(camera) + ".avi"));
    ASSERT_EQ(video.size(), 40u);
    for (int k = 0; k < 40; ++k) {
      const cv::Mat without = ReadMask(dir.path() / "plain", "masks", camera, k);
      const cv::Mat with = ReadMask(dir.path() / "scene", "masks", camera, k);
      const cv::Mat observed = ReadMask(dir.path() / "scene", "observed", camera, k);
      EXPECT_EQ(cv::countNonZero(with & ~without), 0) << camera << " " << k;  // only hidden, never added
      hidden += cv::countNonZero(without & ~with);
      EXPECT_EQ(cv::countNonZero(with & ~observed), 0);  // observed: the mask, passers and the shadow
      // Where the observed mask has more than the walker and the passers could explain,
      // the shadow: the floor is darker there in the video than in the empty room.
      const cv::Mat extra = observed & ~with;
      cv::Mat grey_video, grey_room;
      cv::cvtColor(video[k], grey_video, cv::COLOR_BGR2GRAY);
      cv::cvtColor(room, grey_room, cv::COLOR_BGR2GRAY);
      const int n = cv::countNonZero(extra);
      if (n > 20) {
        darker += (cv::mean(grey_room, extra)[0] - cv::mean(grey_video, extra)[0]) * n;
        shadow_px += n;
      }
    }
  }
  std::printf("occluders and passers hid %d walker pixels; shadow and passers %d px, %.0f grey levels darker\n",
              hidden, shadow_px, shadow_px ? darker / shadow_px : 0.0);
  EXPECT_GT(hidden, 100);
  EXPECT_GT(shadow_px, 500);
  EXPECT_GT(darker / std::max(1, shadow_px), 20);

  // The occluders as a user would paint them (occluders/CAMERA.png): only objects (where
  // the room's picture differs from the plain clip's: the same seed, the same noise), and
  // every walker pixel an object hid is painted. The plain clip has no painting.
  int painted = 0;
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "plain/occluders"));
  const ClipPaths scene_paths{dir.path() / "scene"};
  for (const char* camera : {"cam0", "cam1"}) {
    const cv::Mat room = cv::imread((dir.path() / "scene/background" / (std::string(camera) + ".png")).string());
    const cv::Mat plain_room = cv::imread((dir.path() / "plain/background" / (std::string(camera) + ".png")).string());
    cv::Mat differ;
    cv::absdiff(room, plain_room, differ);
    cv::transform(differ, differ, cv::Matx13f(1, 1, 1));
    const cv::Mat objects = differ > 0;
    const bool has = std::filesystem::exists(scene_paths.Occluders(camera));
    const cv::Mat painting = has ? cv::imread(scene_paths.Occluders(camera).string(), cv::IMREAD_GRAYSCALE)
                                 : cv::Mat::zeros(room.size(), CV_8UC1);
    ASSERT_EQ(painting.size(), room.size());
    EXPECT_EQ(cv::countNonZero(painting & ~objects), 0) << camera;
    painted += cv::countNonZero(painting);
    for (int k = 0; k < 40; ++k) {
      const cv::Mat by_objects = ReadMask(dir.path() / "plain", "masks", camera, k) &
                                 ~ReadMask(dir.path() / "scene", "masks", camera, k) & objects;
      EXPECT_EQ(cv::countNonZero(by_objects & ~painting), 0) << camera << " " << k;
    }
  }
  EXPECT_GT(painted, 0);
}

// A glossy floor: the walker is unchanged (exact masks as without it); the video differs
// from the matt floor's below the walker, where the reflection is, and the observed masks
// hold it there; the degradations are the same (the same seed).
TEST(SyntheticClipTest, AGlossyFloorReflectsTheWalkerBelowTheFeet) {
  const Trial& walk = Walk();
  test::TempDir dir;
  ClipOptions plain = SmallClip();
  plain.max_frames = 30;
  plain.degradations.clutter_blobs = 1;
  ClipOptions glossy = plain;
  glossy.scene.reflection = 0.3;
  RenderClip(walk.skeleton, walk.motion, walk.source, {}, plain, (dir.path() / "plain").string());
  RenderClip(walk.skeleton, walk.motion, walk.source, {}, glossy, (dir.path() / "glossy").string());
  EXPECT_EQ(ReadGroundTruth(dir.path() / "glossy/ground_truth.json").reflection, 0.3);
  EXPECT_EQ(ReadGroundTruth(dir.path() / "plain/ground_truth.json").reflection, 0.0);
  int reflected = 0;
  double inside = 0, outside = 0;
  for (const char* camera : {"cam0", "cam1"}) {
    const std::vector<cv::Mat> plain_video = ReadVideo(dir.path() / "plain" / (std::string(camera) + ".avi"));
    const std::vector<cv::Mat> video = ReadVideo(dir.path() / "glossy" / (std::string(camera) + ".avi"));
    ASSERT_EQ(video.size(), plain_video.size());
    for (int k = 0; k < static_cast<int>(video.size()); ++k) {
      const cv::Mat walker = ReadMask(dir.path() / "glossy", "masks", camera, k);
      ASSERT_EQ(cv::countNonZero(walker != ReadMask(dir.path() / "plain", "masks", camera, k)), 0);
      const cv::Mat observed = ReadMask(dir.path() / "glossy", "observed", camera, k);
      const cv::Mat plain_observed = ReadMask(dir.path() / "plain", "observed", camera, k);
      EXPECT_EQ(cv::countNonZero(plain_observed & ~observed), 0);  // only added to
      const cv::Mat extra = observed & ~plain_observed;
      const int n = cv::countNonZero(extra);
      if (n == 0) continue;
      reflected += n;
      // Below the walker: no added pixel above the middle of the walker's height.
      const cv::Rect box = cv::boundingRect(walker);
      const cv::Rect added = cv::boundingRect(extra);
      EXPECT_GE(added.y, box.y + box.height / 2) << camera << " frame " << k;
      cv::Mat difference;
      cv::absdiff(video[k], plain_video[k], difference);
      cv::transform(difference, difference, cv::Matx13f(1.f / 3, 1.f / 3, 1.f / 3));
      inside += cv::mean(difference, extra)[0] * n;
      cv::Mat near;  // the walker and the reflection, grown past the codec's blur at their edges
      cv::dilate(extra | walker, near, cv::Mat::ones(9, 9, CV_8U));
      outside += cv::mean(difference, ~near)[0];
    }
  }
  std::printf("reflection: %d px observed, %.1f grey levels changed there, %.2f elsewhere\n", reflected,
              reflected ? inside / reflected : 0.0, outside / 60);
  EXPECT_GT(reflected, 300);
  EXPECT_GT(inside / std::max(1, reflected), 12);
  EXPECT_LT(outside / 60, 1.0);
}

// With calibration error the clip's YAMLs (and its ground truth's cameras, the tracker's)
// are a calibration's, and its render cameras the ones that made the images: joints
// project into the exact masks through the render cameras.
TEST(SyntheticClipTest, CalibrationErrorWritesOtherCamerasThanTheRenderingOnes) {
  const Trial& walk = Walk();
  test::TempDir dir;
  ClipOptions options = SmallClip();
  options.max_frames = 10;
  options.calibration_error = 2;
  const ClipSummary summary = RenderClip(walk.skeleton, walk.motion, walk.source, {}, options,
                                         (dir.path() / "clip").string());
  const ClipGroundTruth truth = ReadGroundTruth(dir.path() / "clip/ground_truth.json");
  ASSERT_EQ(truth.render_cameras.size(), 2u);
  const std::vector<Camera> ring = DefaultRig([&] {
    std::vector<Eigen::Matrix3Xd> joints;
    for (const ClipFrame& f : truth.frames) joints.push_back(f.joints_mm);
    return joints;
  }(), options.rig);
  for (int c = 0; c < 2; ++c) {
    const Camera written = ReadCameraYaml((dir.path() / "clip" / (truth.cameras[c].name + ".yaml")).string()).camera;
    EXPECT_NEAR(written.fx, truth.cameras[c].fx, 1e-9);
    EXPECT_NEAR(summary.cameras[c].fx, written.fx, 1e-9);
    EXPECT_NE(written.fx, truth.render_cameras[c].fx);
    // Rendered by the ring (fitted here to the truth's joints, written to 0.01 mm).
    EXPECT_NEAR(truth.render_cameras[c].fx, ring[c].fx, 1e-5 * ring[c].fx);
    EXPECT_GT((written.CentreInWorld() - truth.render_cameras[c].CentreInWorld()).norm(), 0.1);
    EXPECT_LE((written.CentreInWorld() - truth.render_cameras[c].CentreInWorld()).norm(), 60 + 1e-6);
  }
}

// Two walkers sent across each other: each is where --walk put it (its middle frame's root
// at the point given, its walk along the heading given), both are drawn into one mask, and
// the pixels each one shows add up to the mask (what one hides of the other is counted
// once, for the nearer).
TEST(SyntheticClipTest, SeveralWalkersAreDrawnTogetherWhereTheyWereSent) {
  const Trial& a = Walk();
  Trial b;
  b.source = {(test::CmuRoot() / "subjects/07/07.asf").string(), (test::CmuRoot() / "subjects/07/07_01.amc").string()};
  b.skeleton = ReadAsf(b.source.asf);
  b.motion = ReadAmc(b.source.amc, b.skeleton);
  ClipWalker first{a.skeleton, a.motion, a.source, {}, {true, 500, -200, 0, 0}};
  ClipWalker second{b.skeleton, b.motion, b.source, {}, {true, 500, -200, 90, 0}};
  second.body.body_seed = 3;
  test::TempDir dir;
  ClipOptions options = SmallClip();
  const fs::path clip = dir.path() / "clip";
  RenderClip({first, second}, {}, options, clip.string());
  const std::string text = ReadTextFile(clip / "ground_truth.json", "truth");
  const ClipGroundTruth truth = ParseGroundTruth(text, "gt.json");
  EXPECT_EQ(FormatGroundTruth(truth), text);
  ASSERT_EQ(truth.people.size(), 2u);
  ASSERT_EQ(truth.frames.size(), 83u);  // the first walker's trial
  // 07_01 has 316 frames to 07_02's 329: its middle comes 6.5 source frames sooner, so it
  // starts 6.5 / 120 s after the clip: it is in clip frames 2 (source frame 1.5) to 80
  // (313.5; frame 81 would be 317.5, past its last, 315).
  EXPECT_NEAR(truth.people[1].start_s, 6.5 / 120, 1e-12);
  EXPECT_EQ(truth.people[0].frames.size(), 83u);
  ASSERT_EQ(truth.people[1].frames.size(), 79u);
  EXPECT_EQ(truth.people[1].frames.front().frame, 2);
  EXPECT_EQ(truth.people[1].frames.back().frame, 80);
  EXPECT_EQ(truth.people[1].body.body_seed, 3u);
  const Kinematics kinematics_a(a.skeleton), kinematics_b(b.skeleton);
  for (size_t w = 0; w < 2; ++w) {
    const ClipPerson& p = truth.people[w];
    const Motion& motion = w == 0 ? a.motion : b.motion;
    const Kinematics& kinematics = w == 0 ? kinematics_a : kinematics_b;
    ASSERT_FALSE(p.frames.empty());
    for (const ClipPersonFrame& f : p.frames) {
      // Shown at its own time: a source frame nearest to (clip time - start) * 120 (07_01's
      // fall half-way between two).
      EXPECT_LE(std::abs(f.source_frame - (f.frame / 30.0 - p.start_s) * 120), 0.5 + 1e-9) << w << " " << f.frame;
      // A rigid motion of the recorded pose: the same bone lengths and heights.
      const Eigen::Matrix3Xd recorded = kinematics.Compute(motion.Frame(f.source_frame));
      EXPECT_NEAR((f.joints_mm.row(1) - recorded.row(1)).cwiseAbs().maxCoeff(), 0, 0.006);
      EXPECT_NEAR((f.joints_mm.col(5) - f.joints_mm.col(0)).norm(), (recorded.col(5) - recorded.col(0)).norm(), 0.02);
    }
    // Its middle frame's root at (500, -200), its walk towards its heading.
    const Eigen::Matrix3Xd middle = kinematics.Compute(motion.Frame((motion.NumFrames() - 1) / 2));
    const Eigen::Matrix3Xd start = kinematics.Compute(motion.Frame(0)), end = kinematics.Compute(motion.Frame(motion.NumFrames() - 1));
    Eigen::Vector2d walk(end(0, 0) - start(0, 0), end(2, 0) - start(2, 0));
    const double along = std::atan2(walk.y(), walk.x()), heading = (w == 0 ? 0 : 90) * std::numbers::pi / 180;
    const Eigen::Rotation2Dd turn(heading - along);
    for (const ClipPersonFrame& f : p.frames) {
      const Eigen::Matrix3Xd recorded = kinematics.Compute(motion.Frame(f.source_frame));
      const Eigen::Vector2d expected = turn * Eigen::Vector2d(recorded(0, 0) - middle(0, 0), recorded(2, 0) - middle(2, 0)) +
                                       Eigen::Vector2d(500, -200);
      EXPECT_NEAR(f.joints_mm(0, 0), expected.x(), 0.006);
      EXPECT_NEAR(f.joints_mm(2, 0), expected.y(), 0.006);
    }
  }
  // The top level is the first walker's.
  for (size_t k = 0; k < truth.frames.size(); ++k)
    EXPECT_EQ(truth.frames[k].joints_mm, truth.people[0].frames[k].joints_mm);
  // Every pixel of the mask belongs to exactly one walker; at the crossing one hides the
  // other in some camera.
  double least_seen = 1;
  for (size_t c = 0; c < truth.cameras.size(); ++c) {
    for (int k = 0; k < 83; ++k) {
      const cv::Mat mask = cv::imread((clip / "masks" / truth.cameras[c].name / ClipFrameName(k)).string(),
                                      cv::IMREAD_UNCHANGED);
      const int second_at = k - truth.people[1].frames.front().frame;
      const int second = second_at >= 0 && second_at < 79 ? truth.people[1].frames[second_at].visible_px[c] : 0;
      EXPECT_EQ(truth.people[0].frames[k].visible_px[c] + second, cv::countNonZero(mask))
          << truth.cameras[c].name << " frame " << k;
    }
    std::vector<double> counts[2];
    for (size_t w = 0; w < 2; ++w)
      for (const ClipPersonFrame& f : truth.people[w].frames) counts[w].push_back(f.visible_px[c]);
    for (size_t w = 0; w < 2; ++w) {
      std::vector<double> sorted = counts[w];
      std::sort(sorted.begin(), sorted.end());
      least_seen = std::min(least_seen, sorted.front() / sorted[sorted.size() / 2]);
    }
  }
  std::printf("least seen: %.2f of a walker's median pixels\n", least_seen);
  EXPECT_LT(least_seen, 0.6);
  // Malformed people are named.
  const struct {
    const char* from;
    const char* to;
    const char* phrase;
  } cases[] = {
      {"\"id\": 2", "\"id\": 3", "people[1].id"},
      {"\"visible_px\": [", "\"visible_px\": [1, ", "visible_px"},
      {"\"placed\": true", "\"placed\": 1", "people[0].placement.placed"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.from);
    test::ExpectInputError([&] { ParseGroundTruth(test::Replace(text, c.from, c.to), "gt.json"); }, {"gt.json", c.phrase});
  }
  // The first walker cannot be late: the clip is its trial.
  first.placement.delay_s = 0.5;
  test::ExpectInputError([&] { RenderClip({first, second}, {}, options, (dir.path() / "late").string()); },
                         {"07_02.amc", "delay must be 0"});
  EXPECT_FALSE(fs::exists(dir.path() / "late"));
  test::ExpectInputError([&] { RenderClip(std::vector<ClipWalker>(9, second), {}, options, (dir.path() / "nine").string()); },
                         {"1 to 8 walkers"});
}

TEST(ClipFormat, GroundTruthRoundTripAndMalformedInput) {
  const Trial& walk = Walk();
  test::TempDir dir;
  ClipOptions options = SmallClip();
  options.max_frames = 5;
  options.degradations.drop_rate = 0.5;
  RenderClip(walk.skeleton, walk.motion, walk.source, {}, options, (dir.path() / "clip").string());
  const std::string text = ReadTextFile(dir.path() / "clip/ground_truth.json", "truth");
  const ClipGroundTruth truth = ParseGroundTruth(text, "gt.json");
  EXPECT_EQ(FormatGroundTruth(truth), text);
  EXPECT_EQ(text.find("\"scene\""), std::string::npos);  // today's clips: no scene, no render cameras
  EXPECT_EQ(text.find("render_cameras"), std::string::npos);
  // A clip of another world round-trips too, and its new fields are checked.
  ClipOptions other = options;
  other.rig.kind = RigKind::kSurveillance;
  other.rig.width = 160;
  other.rig.height = 120;
  other.body.body_seed = 4;
  other.body.clothing = Clothing::kSkirt;
  other.body.bag = true;
  other.scene.shadow = true;
  other.scene.occluders = 1;
  other.calibration_error = 1;
  RenderClip(walk.skeleton, walk.motion, walk.source, {}, other, (dir.path() / "other").string());
  const std::string other_text = ReadTextFile(dir.path() / "other/ground_truth.json", "truth");
  const ClipGroundTruth other_truth = ParseGroundTruth(other_text, "gt.json");
  EXPECT_EQ(FormatGroundTruth(other_truth), other_text);
  EXPECT_EQ(other_truth.rig, RigKind::kSurveillance);
  EXPECT_EQ(other_truth.body.clothing, Clothing::kSkirt);
  EXPECT_TRUE(other_truth.body.bag);
  EXPECT_EQ(other_truth.body.body_seed, 4u);
  EXPECT_EQ(other_truth.render_cameras.size(), 2u);
  for (const auto& [before, after, phrase] : std::vector<std::tuple<std::string, std::string, std::string>>{
           {"\"rig\": \"surveillance\"", "\"rig\": \"blimp\"", "scene.rig"},
           {"\"clothing\": \"skirt\"", "\"clothing\": \"cape\"", "body_model.clothing"},
           {"\"calibration_error\": 1.0", "\"calibration_error\": -1.0", "scene.calibration_error"},
           {"\"render_cameras\": [", "\"render_cameras\": [{},", "render_cameras"}}) {
    SCOPED_TRACE(before);
    const std::string bad = test::Replace(other_text, before, after);  // (clang 14 cannot capture a binding)
    test::ExpectInputError([&bad] { ParseGroundTruth(bad, "gt.json"); }, {"gt.json", phrase});
  }
  EXPECT_EQ(truth.cameras.size(), 2u);
  EXPECT_EQ(truth.joint_names.size(), walk.skeleton.bones.size());
  const struct {
    const char* from;
    const char* to;
    const char* phrase;
  } cases[] = {
      {"\"version\": 1", "\"version\": 2", "version 2 is not supported"},
      {"\"format\": \"jgpm synthetic clip\"", "\"format\": \"clip\"", "not a synthetic clip"},
      {"\"fx\": ", "\"fx\": -", "invalid camera"},
      {"\"frame\": 1,", "\"frame\": 2,", "frames[1].frame"},
      {"\"joints_mm\": [\n", "\"joints_mm\": [\n[1, 2, 3],\n", "joint_names"},
      {"\"drop_rate\": 0.5", "\"drop_rate\": 1.5", "drop rate"},
      {"\"fps\": 30.0", "\"fps\": 1e999", "number overflow"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.from);
    test::ExpectInputError([&] { ParseGroundTruth(test::Replace(text, c.from, c.to), "gt.json"); }, {"gt.json", c.phrase});
  }
  // A dropped frame's video frame is null; a kept one's is the next in order.
  for (const ClipFrame& f : truth.frames) EXPECT_EQ(f.dropped, f.video_frame < 0);
}

}  // namespace
}  // namespace jgpm
