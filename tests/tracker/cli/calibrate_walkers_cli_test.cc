// `jgpm calibrate --walkers` end to end, against the cameras that rendered the walkers:
// two surveillance cameras (640x480, 4.5 and 5.5 m up) watching real trials walk past at
// several distances and headings (each trial rendered through the rig turned about the
// vertical and moved, which is the same rig seeing a walk elsewhere on the floor); one
// calibrated from the clips' masks, both together from their videos (placed from the
// walkers they share, also when the second camera's videos started later, which must be
// found); and every bad request refused on one line with nothing written.
#include <cmath>
#include <cstdio>
#include <numbers>
#include <regex>

#include <Eigen/Geometry>
#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/videoio.hpp>

#include "calibration/camera.h"
#include "calibration/rig_placement.h"
#include "calibration/walker_calibration.h"
#include "test_support.h"

namespace jgpm {
namespace {

namespace fs = std::filesystem;

using Result = test::CommandResult;
Result Jgpm(const std::string& arguments) { return test::RunJgpm(arguments); }

constexpr double kDeg = std::numbers::pi / 180;

// The rig where the walks happen, the walk at the floor's origin: cam0 4.5 m up, `back_mm`
// + 9.5 m before it, looking 32 degrees down along +z; cam1 5.5 m up, 7 m to the side and
// 4.5 m beyond the walks' middle (at back_mm 0), looking at it. Both turned `yaw_deg` about
// the vertical through the origin: the rig seeing a walk elsewhere on the floor, heading
// elsewhere.
Camera Surveillance(double back_mm, double yaw_deg, int k = 0) {
  const Eigen::Vector3d middle(0, 0, -back_mm);  // the walks' middle on the floor
  Camera camera;
  if (k == 0) {
    const double tilt = 32 * kDeg;
    const Eigen::Vector3d forward(0, -std::sin(tilt), std::cos(tilt));
    const Eigen::Vector3d centre = Eigen::Vector3d(0, 4500, 0) - Eigen::Vector3d(0, 0, 9500 + back_mm);
    camera = LookAtCamera("cam0", 640, 480, 420, centre, centre + forward * 1000);
  } else {
    camera = LookAtCamera("cam1", 640, 480, 480, middle + Eigen::Vector3d(7000, 5500, 4500), middle);
  }
  const Eigen::Vector3d centre = camera.CentreInWorld();
  const Eigen::Matrix3d turn = Eigen::AngleAxisd(yaw_deg * kDeg, Eigen::Vector3d::UnitY()).toRotationMatrix();
  camera.cam_from_world_rotation = camera.cam_from_world_rotation * turn.transpose();
  camera.cam_from_world_translation_mm = -camera.cam_from_world_rotation * (turn * centre);
  return camera;
}

// "name   12.3 +- 4.5" in the command's output.
Estimate Printed(const std::string& out, const std::string& name) {
  std::smatch m;
  EXPECT_TRUE(std::regex_search(out, m, std::regex(name + " +([-0-9.]+) \\+- ([0-9.]+)"))) << name << "\n" << out;
  return m.empty() ? Estimate{} : Estimate{std::stod(m[1]), std::stod(m[2])};
}

class CalibrateWalkersCli : public testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new test::TempDir;
    const char* trials[] = {"07/07_02", "07/07_03", "35/35_12", "35/35_16", "39/39_12", "02/02_01", "39/39_13",
                            "07/07_04", "35/35_15", "39/39_10"};
    for (int k = 0; k < 10; ++k) {
      std::string cameras;
      for (int c = 0; c < 2; ++c) {
        CameraFile file;
        file.camera = Surveillance((k % 5) * 2500.0 - 4000, (k * 67) % 360, c);
        file.has_extrinsics = true;
        const fs::path yaml = dir_->path() / ("walk" + std::to_string(k) + "_cam" + std::to_string(c) + ".yaml");
        WriteCameraYaml(file, yaml.string());
        cameras += " --camera " + yaml.string();
      }
      const fs::path clip = dir_->path() / ("walk" + std::to_string(k));
      const std::string trial = trials[k];
      const Result r = Jgpm("render --amc " + (test::CmuRoot() / "subjects" / (trial + ".amc")).string() + cameras +
                            " --max-frames 120 --no-contact-sheet --out " + clip.string());
      ASSERT_EQ(r.status, 0) << r.err;
      clips_.push_back(clip.string());
    }
  }
  static void TearDownTestSuite() {
    delete dir_;
    clips_.clear();
  }
  static test::TempDir* dir_;
  static std::vector<std::string> clips_;
};
test::TempDir* CalibrateWalkersCli::dir_ = nullptr;
std::vector<std::string> CalibrateWalkersCli::clips_;

TEST_F(CalibrateWalkersCli, FindsTheCameraThatRenderedTheWalks) {
  std::string walkers;
  for (const std::string& clip : clips_) walkers += " --walkers " + clip;
  const fs::path out = dir_->path() / "found.yaml";
  const Result r = Jgpm("calibrate" + walkers + " --person-height 1.66 --out " + out.string());
  ASSERT_EQ(r.status, 0) << r.out << r.err;
  std::printf("%s", r.out.c_str());  // the figures, for the log
  const Camera found = ReadCameraYaml(out.string()).camera;
  const Camera truth = Surveillance(0, 0);
  const CameraAngles angles = AnglesOf(found), true_angles = AnglesOf(truth);
  // The printed figures are the written camera's.
  const Estimate focal = Printed(r.out, "focal length"), height = Printed(r.out, "height"),
                 tilt = Printed(r.out, "tilt"), roll = Printed(r.out, "roll");
  EXPECT_NEAR(focal.value, found.fx, 0.1);
  EXPECT_NEAR(height.value, angles.height_mm, 1);
  EXPECT_NEAR(tilt.value, angles.tilt_deg, 0.01);
  // Within the bounds (focal and height 5%, angles 2 degrees) up to the sampling
  // error of ten 2.5 s walks, and within 2.5 of the stated uncertainties. The walkers'
  // mean height is given (the subjects' 1.66 m) so that what is checked is the geometry.
  EXPECT_NEAR(found.fx, truth.fx, std::min(0.10 * truth.fx, 2.5 * focal.sd)) << r.out;
  EXPECT_NEAR(angles.height_mm, true_angles.height_mm, std::min(0.10 * true_angles.height_mm, 2.5 * height.sd)) << r.out;
  EXPECT_NEAR(angles.tilt_deg, true_angles.tilt_deg, std::min(2.5, 2.5 * tilt.sd)) << r.out;
  EXPECT_NEAR(angles.roll_deg, true_angles.roll_deg, std::min(2.0, 2.5 * roll.sd)) << r.out;
  EXPECT_LT(focal.sd, 0.10 * focal.value);
  std::string why;
  EXPECT_TRUE(found.Check(&why)) << why;
}

TEST_F(CalibrateWalkersCli, PlacesTwoCamerasFromTheWalkersTheyShare) {
  // Each walk is one take: both cameras' videos, which started together.
  std::string walkers;
  for (const std::string& clip : clips_) walkers += " --walkers " + clip + "/cam0.avi," + clip + "/cam1.avi";
  const fs::path out = dir_->path() / "rig";
  const Result r = Jgpm("calibrate" + walkers + " --person-height 1.66 --out " + out.string());
  ASSERT_EQ(r.status, 0) << r.out << r.err;
  std::printf("%s", r.out.c_str());  // the figures, for the log
  EXPECT_NE(r.out.find("placed from the walkers they share"), std::string::npos);
  // The truth in cam0's world: its floor point the origin (the walks' middle is 9.5 m
  // ahead of it), +z its view.
  std::vector<Camera> truth, found;
  for (int k = 0; k < 2; ++k) {
    truth.push_back(Surveillance(0, 0, k));
    truth[k].cam_from_world_translation_mm -= truth[k].cam_from_world_rotation * Eigen::Vector3d(0, 0, 9500);
    found.push_back(ReadCameraYaml((out / ("cam" + std::to_string(k) + ".yaml")).string()).camera);
    EXPECT_EQ(found[k].name, "cam" + std::to_string(k));
  }
  ASSERT_NEAR(truth[0].CentreInWorld().norm(), 4500, 1e-6);
  // The bounds for each camera: focal length 5%, angles 2 degrees. The heights rest
  // on the walkers' stature as their silhouettes show it: from these videos 4.6% and 3.3%
  // low (7.4% and 8.0% while the learnt background's margin was filled in from the room
  // around, which left the front camera's walkers wide ghosts): within 6%, the 5%
  // and the sampling error of ten walks; and their ratio within 3%.
  for (int k = 0; k < 2; ++k) {
    SCOPED_TRACE("cam" + std::to_string(k));
    const CameraAngles angles = AnglesOf(found[k]), true_angles = AnglesOf(truth[k]);
    EXPECT_NEAR(found[k].fx, truth[k].fx, 0.05 * truth[k].fx) << r.out;
    EXPECT_NEAR(angles.tilt_deg, true_angles.tilt_deg, 2) << r.out;
    EXPECT_NEAR(angles.roll_deg, true_angles.roll_deg, 2) << r.out;
    EXPECT_NEAR(angles.height_mm, true_angles.height_mm, 0.06 * true_angles.height_mm) << r.out;
  }
  EXPECT_NEAR(found[1].CentreInWorld().y() / found[0].CentreInWorld().y(),
              truth[1].CentreInWorld().y() / truth[0].CentreInWorld().y(), 0.03 * 5500 / 4500)
      << r.out;
  // cam1's place relative to cam0: its view's turn within 2 degrees, its floor point within
  // 4% of its distance at the scale the heights found.
  EXPECT_NEAR(YawOf(found[1]), YawOf(truth[1]), 2) << r.out;
  const double scale = found[0].CentreInWorld().y() / truth[0].CentreInWorld().y();
  const Eigen::Vector3d at = found[1].CentreInWorld(), expected = scale * truth[1].CentreInWorld();
  EXPECT_LT(Eigen::Vector2d(at.x() - expected.x(), at.z() - expected.z()).norm(),
            0.04 * Eigen::Vector2d(expected.x(), expected.z()).norm())
      << r.out;
}

// `video` without its first `frames` frames: the same camera's video started that much later.
void WriteStartedLate(const fs::path& video, int frames, const fs::path& out) {
  cv::VideoCapture in(video.string());
  ASSERT_TRUE(in.isOpened()) << video;
  cv::VideoWriter writer(out.string(), cv::VideoWriter::fourcc('M', 'J', 'P', 'G'), in.get(cv::CAP_PROP_FPS),
                         cv::Size(static_cast<int>(in.get(cv::CAP_PROP_FRAME_WIDTH)),
                                  static_cast<int>(in.get(cv::CAP_PROP_FRAME_HEIGHT))));
  ASSERT_TRUE(writer.isOpened()) << out;
  cv::Mat image;
  for (int k = 0; in.read(image); ++k)
    if (k >= frames) writer.write(image);
}

TEST_F(CalibrateWalkersCli, FindsHowMuchLaterTheSecondCamerasVideosStarted) {
  // cam1's videos started 9 frames (0.3 s) after cam0's, in every take. (The tightest
  // placement alone is 11 frames late on these walks: the offset is the tightness
  // parabola's vertex, rig_placement.cc.)
  std::string walkers;
  for (size_t k = 0; k < clips_.size(); ++k) {
    const fs::path late = dir_->path() / ("late" + std::to_string(k) + ".avi");
    WriteStartedLate(fs::path(clips_[k]) / "cam1.avi", 9, late);
    walkers += " --walkers " + clips_[k] + "/cam0.avi," + late.string();
  }
  const fs::path out = dir_->path() / "late_rig";
  const Result r = Jgpm("calibrate" + walkers + " --person-height 1.66 --out " + out.string());
  ASSERT_EQ(r.status, 0) << r.out << r.err;
  std::printf("%s", r.out.c_str());  // the figures, for the log
  EXPECT_NE(r.out.find("its video started 0.30 s (9 frames) after cam0's"), std::string::npos) << r.out;
  const Camera cam0 = ReadCameraYaml((out / "cam0.yaml").string()).camera;
  const Camera cam1 = ReadCameraYaml((out / "cam1.yaml").string()).camera;
  EXPECT_EQ(cam0.clock_offset_s, 0);
  EXPECT_NEAR(cam1.clock_offset_s, 0.3, 1e-9);
  // Placed as the truth is (the synchronised test's bounds).
  Camera truth = Surveillance(0, 0, 1);
  EXPECT_NEAR(YawOf(cam1), YawOf(truth), 2) << r.out;
  EXPECT_NEAR(AnglesOf(cam1).tilt_deg, AnglesOf(truth).tilt_deg, 2) << r.out;
}

TEST_F(CalibrateWalkersCli, BadRequestsGiveOneLineAndWriteNothing) {
  const fs::path out = dir_->path() / "never.yaml";
  // A walk's video as a folder of frames (as jgpm capture saves them).
  const fs::path frames = dir_->path() / "frames";
  fs::create_directories(frames);
  cv::VideoCapture video(clips_[0] + "/cam0.avi");
  cv::Mat image;
  for (int k = 0; video.read(image); ++k) ASSERT_TRUE(cv::imwrite((frames / cv::format("%06d.png", k)).string(), image));
  // Nobody: the empty scene, 60 frames. A moving camera: the walk's video panned 120 px
  // across its frames.
  const fs::path nobody = dir_->path() / "nobody.avi", pan = dir_->path() / "pan.avi";
  {
    const cv::Mat scene = cv::imread(clips_[0] + "/background/cam0.png");
    ASSERT_FALSE(scene.empty());
    cv::VideoWriter empty(nobody.string(), cv::VideoWriter::fourcc('M', 'J', 'P', 'G'), 30, scene.size());
    for (int k = 0; k < 60; ++k) empty.write(scene);
    cv::VideoCapture walk(clips_[0] + "/cam0.avi");
    std::vector<cv::Mat> shots;
    while (walk.read(image)) shots.push_back(image.clone());
    ASSERT_FALSE(shots.empty());
    cv::VideoWriter panned(pan.string(), cv::VideoWriter::fourcc('M', 'J', 'P', 'G'), 30,
                           cv::Size(shots[0].cols - 120, shots[0].rows));
    for (size_t k = 0; k < shots.size(); ++k) {
      const int x = static_cast<int>(120 * k / shots.size());
      panned.write(shots[k](cv::Rect(x, 0, shots[k].cols - 120, shots[k].rows)).clone());
    }
  }
  const std::string o = " --out " + out.string();
  struct Case {
    std::string arguments;
    int status;
    std::string says;
  };
  const Case cases[] = {
      // One walk, along one line: the focal length is not determined.
      {"calibrate --walkers " + clips_[0] + o, 1, "do not determine"},
      // The same through background subtraction of its video.
      {"calibrate --walkers " + clips_[0] + "/cam0.avi" + o, 1, "do not determine"},
      {"calibrate --walkers " + clips_[0] + " --person-height 170" + o, 2, "metres"},
      {"calibrate --walkers " + clips_[0] + " --images " + clips_[0] + o, 2, "excludes"},
      {"calibrate --walkers " + (dir_->path() / "nowhere.avi").string() + o, 2, "nowhere.avi"},
      {"calibrate --person-height 1.7" + o, 2, "--walkers"},
      {"calibrate" + o, 1, "--walkers VIDEO"},
      {"calibrate --walkers " + frames.string() + o, 1, "--fps"},
      {"calibrate --walkers " + frames.string() + " --fps 30" + o, 1, "do not determine"},
      {"calibrate --walkers " + nobody.string() + o, 1, "got 0"},
      {"calibrate --walkers " + pan.string() + o, 1, "needs a fixed camera"},
      // A live camera (the software one playing the empty scene): watched for its frames,
      // then refused the same way; and tracking from it, calibrated from its first second.
      {"calibrate --walkers fake:" + nobody.string() + " --max-frames 30" + o, 1, "got 0"},
      {"track --model " + (dir_->path() / "none.json").string() + " --device fake:" + nobody.string() +
           " --calibrate-from-walkers --calibration-seconds 1 --out " + (dir_->path() / "track").string(),
       1, "got 0"},
      {"calibrate --walkers fake" + o, 2, "does not exist"},
      // Tracking with the camera calibrated first: the calibration's refusal stops it.
      {"track --model " + (dir_->path() / "none.json").string() + " --video " + clips_[0] + "/cam0.avi" +
           " --calibrate-from-walkers --out " + (dir_->path() / "track").string(),
       1, "do not determine"},
      {"track --model m.json --clip " + clips_[0] + " --calibrate-from-walkers --out " +
           (dir_->path() / "track").string(),
       1, "--video files"},
      // Several cameras: every take lists one video per camera, backgrounds one per camera.
      {"calibrate --walkers " + clips_[0] + "/cam0.avi," + clips_[0] + "/cam1.avi --walkers " + clips_[1] +
           "/cam0.avi" + o,
       1, "lists 1 cameras' videos"},
      {"calibrate --walkers " + clips_[0] + "/cam0.avi," + clips_[0] + "/cam1.avi --background " + clips_[0] +
           "/background/cam0.png" + o,
       1, "one per camera"},
      {"calibrate --walkers " + clips_[0] + "/cam0.avi," + (dir_->path() / "nowhere.avi").string() + o, 2,
       "nowhere.avi"},
      // Both cameras' walks in the first take, the second camera's one clip late: the
      // clocks disagree and nobody is seen by both at once.
      {"calibrate --walkers " + clips_[0] + "/cam0.avi," + clips_[1] + "/cam1.avi --walkers " + clips_[1] +
           "/cam0.avi," + clips_[2] + "/cam1.avi --walkers " + clips_[2] + "/cam0.avi," + clips_[3] +
           "/cam1.avi --walkers " + clips_[3] + "/cam0.avi," + clips_[4] + "/cam1.avi --walkers " + clips_[4] +
           "/cam0.avi," + clips_[0] + "/cam1.avi" + o,
       1, "shares too few walkers"},
      {"track --model m.json --video " + clips_[0] + "/cam0.avi --camera " + clips_[0] + "/cam0.yaml" +
           " --calibrate-from-walkers --out " + (dir_->path() / "track").string(),
       2, "excludes"},
  };
  for (const Case& c : cases) {
    const Result r = Jgpm(c.arguments);
    EXPECT_EQ(r.status, c.status) << c.arguments << "\n" << r.err;
    EXPECT_NE(r.err.find(c.says), std::string::npos) << c.arguments << "\n" << r.err;
    EXPECT_EQ(test::CountLines(r.err.substr(r.err.rfind("jgpm: error"))), 1) << r.err;
    EXPECT_FALSE(fs::exists(out)) << c.arguments;
    EXPECT_FALSE(fs::exists(dir_->path() / "track")) << c.arguments;
  }
}

}  // namespace
}  // namespace jgpm
