// `jgpm calibrate` end to end on rendered chessboard images: the YAML it writes holds the
// camera that rendered them; bad options give one line, a non-zero exit and no file.
#include <cmath>
#include <fstream>
#include <numbers>

#include <Eigen/Geometry>
#include <gtest/gtest.h>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "calibration/camera.h"
#include "calibration/synthetic_chessboard.h"
#include "calibration/true_camera.h"
#include "test_support.h"

namespace jgpm {
namespace {

namespace fs = std::filesystem;


using Result = test::CommandResult;
Result Jgpm(const std::string& arguments) { return test::RunJgpm(arguments); }

using test::TrueCamera;

// A folder of chessboard images (9x6 inner corners, 30 mm squares) seen by TrueCamera(),
// a blank image, a text file that is not an image, and a floor image: a 7x4 board of
// 150 mm squares on the floor, first corner at the origin, seen from `floor_camera`.
class CalibrateCli : public testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new test::TempDir;
    fs::create_directories(Images());
    const ChessboardRenderer renderer(TrueCamera(), 3);
    SyntheticChessboardOptions board;
    board.noise_stddev = 2;
    // Board centre (camera frame), tilt about an in-plane axis at `axis` degrees.
    const struct {
      double tilt_deg, axis_deg;
      Eigen::Vector3d centre_mm;
    } views[] = {{25, 45, {-190, -97, 480}},  {25, 135, {123, -125, 480}}, {-25, 45, {177, 101, 480}},
                 {-25, 135, {-134, 130, 480}}, {30, 90, {-40, 0, 540}},     {-30, 0, {0, 20, 520}}};
    int v = 0;
    for (const auto& view : views) {
      BoardPose pose;
      const Eigen::Vector3d axis(std::cos(view.axis_deg * std::numbers::pi / 180), std::sin(view.axis_deg * std::numbers::pi / 180), 0);
      pose.world_from_board_rotation = Eigen::AngleAxisd(view.tilt_deg * std::numbers::pi / 180, axis).toRotationMatrix();
      pose.first_corner_in_world_mm = view.centre_mm - pose.world_from_board_rotation * Eigen::Vector3d(120, 75, 0);
      board.noise_seed = ++v;
      ASSERT_TRUE(cv::imwrite((Images() / ("board_" + std::to_string(v) + ".png")).string(),
                              renderer.Render(TrueCamera(), board, pose)));
    }
    ASSERT_TRUE(cv::imwrite((Images() / "blank.png").string(), cv::Mat(480, 640, CV_8UC1, cv::Scalar(180))));
    std::ofstream(Images() / "notes.txt") << "not an image, not looked at\n";

    SyntheticChessboardOptions floor_board;
    floor_board.cols = 7;
    floor_board.rows = 4;
    floor_board.square_mm = 150;
    floor_board.noise_stddev = 2;
    BoardPose on_floor;  // world = (x_board, -z_board, y_board)
    on_floor.world_from_board_rotation << 1, 0, 0, 0, 0, -1, 0, 1, 0;
    const Eigen::Vector3d middle = on_floor.CornerInWorld(3, 1.5, 150);
    floor_camera_ = new Camera(LookAtCamera("floor", 640, 480, 500, middle + Eigen::Vector3d(700, 1500, -1900), middle));
    floor_camera_->fx = TrueCamera().fx;
    floor_camera_->fy = TrueCamera().fy;
    floor_camera_->cx = TrueCamera().cx;
    floor_camera_->cy = TrueCamera().cy;
    floor_camera_->distortion = TrueCamera().distortion;
    ASSERT_TRUE(cv::imwrite(FloorImage().string(), renderer.Render(*floor_camera_, floor_board, on_floor)));
  }
  static void TearDownTestSuite() {
    delete floor_camera_;
    delete dir_;
  }

  static fs::path Images() { return dir_->path() / "images"; }
  static fs::path FloorImage() { return dir_->path() / "floor.png"; }
  static fs::path Out() { return dir_->path() / "cam.yaml"; }
  static std::string Calibrate() {
    return "calibrate --images " + Images().string() + " --board 9x6 --square 30 --out " + Out().string();
  }
  void SetUp() override { fs::remove(Out()); }

  static test::TempDir* dir_;
  static Camera* floor_camera_;
};
test::TempDir* CalibrateCli::dir_ = nullptr;
Camera* CalibrateCli::floor_camera_ = nullptr;

TEST_F(CalibrateCli, Help) {
  const Result r = Jgpm("calibrate --help");
  EXPECT_EQ(r.status, 0);
  EXPECT_NE(r.out.find("--floor-image"), std::string::npos);
}

TEST_F(CalibrateCli, WritesTheCameraThatRenderedTheImages) {
  const Result r = Jgpm(Calibrate() + " --name left");
  std::printf("%s", r.out.c_str());
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.err, "");
  // One line per image, in name order; the text file is not an image.
  EXPECT_NE(r.out.find("blank.png                    rejected  no 9x6 chessboard found"), std::string::npos);
  for (int v = 1; v <= 6; ++v) {
    EXPECT_NE(r.out.find("board_" + std::to_string(v) + ".png                  used      RMS "), std::string::npos) << v;
  }
  EXPECT_LT(r.out.find("blank.png"), r.out.find("board_1.png"));
  EXPECT_EQ(r.out.find("notes.txt"), std::string::npos);
  EXPECT_NE(r.out.find("over 6 of 7 images"), std::string::npos);
  EXPECT_NE(r.out.find("not placed"), std::string::npos);

  const CameraFile file = ReadCameraYaml(Out().string());
  EXPECT_EQ(file.camera.name, "left");
  EXPECT_EQ(file.camera.width, 640);
  EXPECT_EQ(file.camera.height, 480);
  EXPECT_NEAR(file.camera.fx, TrueCamera().fx, 0.005 * TrueCamera().fx);
  EXPECT_NEAR(file.camera.fy, TrueCamera().fy, 0.005 * TrueCamera().fy);
  EXPECT_NEAR(file.camera.cx, TrueCamera().cx, 3);
  EXPECT_NEAR(file.camera.cy, TrueCamera().cy, 3);
  EXPECT_GT(file.avg_reprojection_error_px, 0);
  EXPECT_LT(file.avg_reprojection_error_px, 0.2);
  // Unplaced, so `jgpm render --camera` and the tracker ask for a placement first.
  EXPECT_FALSE(file.has_extrinsics);
}

TEST_F(CalibrateCli, PlacesTheCameraByTheFloorBoard) {
  const Result r = Jgpm(Calibrate() + " --floor-image " + FloorImage().string() + " --floor-board 7x4 --floor-square 150");
  std::printf("%s", r.out.c_str());
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("placed by the 7x4 floor board"), std::string::npos);
  const CameraFile file = ReadCameraYaml(Out().string());
  EXPECT_TRUE(file.has_extrinsics);
  // With intrinsics from six images; the placement alone, with the true ones, is within
  // 1.3 mm (calibration/chessboard_test).
  const double centre_error = (file.camera.CentreInWorld() - floor_camera_->CentreInWorld()).norm();
  const double rotation_error_deg = Eigen::AngleAxisd(file.camera.cam_from_world_rotation *
                                                      floor_camera_->cam_from_world_rotation.transpose()).angle() * 180 / std::numbers::pi;
  std::printf("camera centre %.2f mm, rotation %.3f degrees from the truth\n", centre_error, rotation_error_deg);
  EXPECT_LT(centre_error, 25);
  EXPECT_LT(rotation_error_deg, 0.3);
}

TEST_F(CalibrateCli, TakesThePoseFromAFile) {
  const Camera placed = LookAtCamera("p", 640, 480, 500, {1000, 1600, -3000}, {0, 900, 0});
  CameraFile pose_source;
  pose_source.camera = placed;
  pose_source.has_extrinsics = true;
  const fs::path pose = dir_->path() / "pose.yaml";
  WriteCameraYaml(pose_source, pose.string());
  const Result r = Jgpm(Calibrate() + " --pose " + pose.string());
  ASSERT_EQ(r.status, 0) << r.err;
  const CameraFile file = ReadCameraYaml(Out().string());
  EXPECT_EQ(file.camera.cam_from_world_rotation, placed.cam_from_world_rotation);
  EXPECT_EQ(file.camera.cam_from_world_translation_mm, placed.cam_from_world_translation_mm);
  EXPECT_NE(file.camera.fx, placed.fx);  // the intrinsics are the calibrated ones
}

// Bad options and inputs: exit 2 for what the option parser catches, 1 for the rest; one
// line on stderr naming the option or file; no output file.
TEST_F(CalibrateCli, BadInputsGiveOneLineAndNoFile) {
  const fs::path empty = dir_->path() / "empty";
  fs::create_directories(empty);
  const fs::path no_pose = dir_->path() / "no_pose.yaml";
  std::ofstream(no_pose) << "%YAML:1.0\n---\ncamera_name: \"x\"\n";
  // Images without a board (noise is given up quickly with --fast-check only).
  const fs::path no_boards = dir_->path() / "no_boards";
  fs::create_directories(no_boards);
  ASSERT_TRUE(cv::imwrite((no_boards / "grey.png").string(), cv::Mat(480, 640, CV_8UC1, cv::Scalar(180))));
  cv::Mat noise(480, 640, CV_8UC1);
  cv::randu(noise, 0, 256);
  ASSERT_TRUE(cv::imwrite((no_boards / "noise.png").string(), noise));
  std::ofstream(no_boards / "broken.jpg") << "not a JPEG";
  const std::string images = " --images " + Images().string(), out = " --out " + Out().string();
  const struct {
    std::string arguments;
    int status;
    std::vector<std::string> phrases;
  } cases[] = {
      {"calibrate" + images + " --board 9by6 --square 30" + out, 2, {"--board", "COLSxROWS", "9by6"}},
      {"calibrate" + images + " --board 9x2 --square 30" + out, 2, {"--board", "at least 3"}},
      {"calibrate" + images + " --board 9x6 --square -3" + out, 2, {"--square"}},
      {"calibrate" + images + " --board 9x6 --square 0" + out, 2, {"--square"}},
      {"calibrate" + images + " --board 9x6 --square thirty" + out, 2, {"--square"}},
      {"calibrate --images " + (dir_->path() / "nowhere").string() + " --board 9x6 --square 30" + out, 2,
       {"--images", "nowhere"}},
      {"calibrate --images " + empty.string() + " --board 9x6 --square 30" + out, 1,
       {"--images " + empty.string(), "no .png"}},
      {"calibrate" + images + " --board 9x6 --square 30" + out + " --floor-image " + FloorImage().string() +
           " --pose " + no_pose.string(),
       2, {"--pose", "--floor-image"}},
      {"calibrate" + images + " --board 9x6 --square 30" + out + " --pose " + no_pose.string(), 1,
       {no_pose.string(), "cam_from_world_rotation"}},
      {"calibrate" + images + " --board 9x6 --square 30" + out + " --distortion 6", 2, {"--distortion"}},
      {"calibrate" + images + " --board 9x6 --square 30 --out " + (dir_->path() / "nowhere" / "cam.yaml").string(), 1,
       {"--out", "no such folder"}},
      {"calibrate --images " + no_boards.string() + " --board 9x6 --square 30 --fast-check" + out, 1,
       {no_boards.string() + ": 0 usable chessboard images of 3", "grey.png (no 9x6 chessboard found)",
        "noise.png (no 9x6 chessboard found)", "broken.jpg (not a readable image)"}},
      // A floor board with both counts even has no first corner to go by.
      {"calibrate" + images + " --board 9x6 --square 30" + out + " --floor-image " + FloorImage().string() +
           " --floor-board 8x4",
       1, {"8x4", "one odd and one even"}},
  };
  for (const auto& c : cases) {
    const Result r = Jgpm(c.arguments);
    EXPECT_EQ(r.status, c.status) << c.arguments << "\n" << r.err;
    EXPECT_EQ(test::CountLines(r.err), 1) << c.arguments << "\n" << r.err;
    EXPECT_NE(r.err.find("jgpm: error:"), std::string::npos) << r.err;
    for (const std::string& phrase : c.phrases) EXPECT_NE(r.err.find(phrase), std::string::npos) << r.err << "lacks " << phrase;
    EXPECT_FALSE(fs::exists(Out())) << c.arguments;
  }
}

}  // namespace
}  // namespace jgpm
