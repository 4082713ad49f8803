// Calibration against the camera that rendered the images (synthetic_chessboard.h): the
// recovered intrinsics, board poses and floor placement are compared with the truth.
#include "calibration/chessboard.h"

#include <cmath>
#include <cstdio>
#include <numbers>

#include <Eigen/Geometry>
#include <gtest/gtest.h>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "calibration/synthetic_chessboard.h"
#include "calibration/true_camera.h"
#include "io/base/error.h"
#include "test_support.h"

namespace jgpm {
namespace {

namespace fs = std::filesystem;

double Rad(double deg) { return deg * std::numbers::pi / 180; }
double Deg(double rad) { return rad * 180 / std::numbers::pi; }

using test::TrueCamera;

// Its rays take about 2 s to work out: once for the whole program.
const ChessboardRenderer& Renderer() {
  static const ChessboardRenderer renderer(TrueCamera());
  return renderer;
}

SyntheticChessboardOptions Board(double square_mm) {
  SyntheticChessboardOptions board;
  board.cols = 9;
  board.rows = 6;
  board.square_mm = square_mm;
  board.noise_stddev = 2;
  return board;
}

ChessboardOptions Options(double square_mm) {
  ChessboardOptions options;
  options.cols = 9;
  options.rows = 6;
  options.square_mm = square_mm;
  return options;
}

// A board tilted by `tilt_deg` about the in-plane axis at `axis_deg` from the camera's x
// axis, turned by `roll_deg` about its normal, its centre at `centre_mm` (camera frame).
struct View {
  double tilt_deg;
  double axis_deg;
  double roll_deg;
  Eigen::Vector3d centre_mm;
};

BoardPose PoseOf(const View& v, const SyntheticChessboardOptions& board) {
  const Eigen::Vector3d axis(std::cos(Rad(v.axis_deg)), std::sin(Rad(v.axis_deg)), 0);
  BoardPose pose;
  pose.world_from_board_rotation = (Eigen::AngleAxisd(Rad(v.tilt_deg), axis) *
                                    Eigen::AngleAxisd(Rad(v.roll_deg), Eigen::Vector3d::UnitZ())).toRotationMatrix();
  const Eigen::Vector3d middle((board.cols - 1) * board.square_mm / 2, (board.rows - 1) * board.square_mm / 2, 0);
  pose.first_corner_in_world_mm = v.centre_mm - pose.world_from_board_rotation * middle;
  return pose;
}

// The board's squares wholly in the image, 2 px from the edges (sampled along their
// outline, which distortion bends). The white margin may be cut by the image edge.
bool SquaresInView(const Camera& camera, const SyntheticChessboardOptions& board, const BoardPose& pose) {
  const double x0 = -1, x1 = board.cols, y0 = -1, y1 = board.rows;  // in squares
  for (int k = 0; k <= 40; ++k) {
    const double u = k / 40.0;
    for (const Eigen::Vector2d& p : {Eigen::Vector2d(x0 + u * (x1 - x0), y0), Eigen::Vector2d(x0 + u * (x1 - x0), y1),
                                     Eigen::Vector2d(x0, y0 + u * (y1 - y0)), Eigen::Vector2d(x1, y0 + u * (y1 - y0))}) {
      Eigen::Vector2d pixel;
      if (!camera.Project(pose.CornerInWorld(p.x(), p.y(), board.square_mm), &pixel)) return false;
      if (pixel.x() < 2 || pixel.y() < 2 || pixel.x() > camera.width - 3 || pixel.y() > camera.height - 3) return false;
    }
  }
  return true;
}

// Tilts of 20-35 degrees in many directions: four views reaching into the image's
// corners, four to its edges, six nearer the middle, near and far, rolled.
const View kViews[] = {
    {25, 45, 0, {-190, -97, 480}},  {25, 135, 0, {123, -125, 480}},  {-25, 45, 0, {177, 101, 480}},
    {-25, 135, 0, {-134, 130, 480}}, {30, 90, 5, {-150, 0, 520}},     {-30, 90, -5, {150, 0, 520}},
    {30, 0, 0, {0, -120, 520}},     {-30, 0, 0, {0, 120, 520}},      {20, 30, 90, {0, 0, 480}},
    {35, 315, 0, {-60, 40, 640}},   {35, 225, 0, {60, 40, 640}},     {30, 160, -15, {0, -20, 450}},
    {20, 200, 180, {0, 0, 500}},    {35, 20, 5, {0, 0, 700}},
};
constexpr int kNumViews = static_cast<int>(std::size(kViews));

// Renders the first `count` views to `dir`/view_NN.png; returns the paths.
std::vector<std::string> WriteViews(const fs::path& dir, int count = kNumViews) {
  const SyntheticChessboardOptions board = Board(30);
  std::vector<std::string> paths;
  for (int v = 0; v < count; ++v) {
    SyntheticChessboardOptions noisy = board;
    noisy.noise_seed = static_cast<uint32_t>(v + 1);
    const BoardPose pose = PoseOf(kViews[v], board);
    EXPECT_TRUE(SquaresInView(TrueCamera(), board, pose)) << "test bug: view " << v << " leaves the image";
    char name[32];
    std::snprintf(name, sizeof(name), "view_%02d.png", v);
    paths.push_back((dir / name).string());
    EXPECT_TRUE(cv::imwrite(paths.back(), Renderer().Render(TrueCamera(), noisy, pose)));
  }
  return paths;
}

std::string WriteBlank(const fs::path& dir) {
  const std::string path = (dir / "blank.png").string();
  EXPECT_TRUE(cv::imwrite(path, cv::Mat(480, 640, CV_8UC1, cv::Scalar(180))));
  return path;
}

TEST(Chessboard, OptionsCheck) {
  std::string why;
  EXPECT_TRUE(ChessboardOptions().Check(&why)) << why;
  ChessboardOptions o;
  o.cols = 2;
  EXPECT_FALSE(o.Check(&why));
  EXPECT_NE(why.find("3x3"), std::string::npos);
  o = ChessboardOptions();
  o.square_mm = 0;
  EXPECT_FALSE(o.Check(&why));
  o.square_mm = std::nan("");
  EXPECT_FALSE(o.Check(&why));
  o = ChessboardOptions();
  o.distortion_coefficients = 6;
  EXPECT_FALSE(o.Check(&why));
  o = ChessboardOptions();
  o.subpixel_half_window_px = 0;
  EXPECT_FALSE(o.Check(&why));
}

TEST(Chessboard, OpenCvFindsTheRenderedCornersInOrder) {
  // The renderer's corner (0, 0) is OpenCV's first corner, and the detected corners are
  // where the camera projects the board's corners.
  const SyntheticChessboardOptions board = Board(30);
  double worst = 0, sum = 0;
  int count = 0;
  for (const View& view : kViews) {
    const BoardPose pose = PoseOf(view, board);
    std::vector<Eigen::Vector2d> truth, found;
    ASSERT_TRUE(ChessboardCornerPixels(TrueCamera(), board, pose, &truth));
    ASSERT_TRUE(FindChessboardCorners(Renderer().Render(TrueCamera(), board, pose), Options(30), &found));
    ASSERT_EQ(found.size(), truth.size());
    for (size_t i = 0; i < found.size(); ++i) {
      const double e = (found[i] - truth[i]).norm();
      worst = std::max(worst, e);
      sum += e * e;
      ++count;
    }
  }
  std::printf("detected corners vs the truth over %d views: RMS %.4f px, max %.4f px\n", kNumViews,
              std::sqrt(sum / count), worst);
  EXPECT_LT(std::sqrt(sum / count), 0.06);
  EXPECT_LT(worst, 0.2);
}

TEST(Chessboard, NoBoardInNoise) {
  cv::Mat noise(480, 640, CV_8UC1);
  cv::randu(noise, 0, 256);
  ChessboardOptions fast = Options(30);
  fast.fast_check = true;  // without it OpenCV searches the noise for about 4 s
  std::vector<Eigen::Vector2d> corners;
  EXPECT_FALSE(FindChessboardCorners(noise, fast, &corners));
  EXPECT_TRUE(corners.empty());
  EXPECT_FALSE(FindChessboardCorners(cv::Mat(480, 640, CV_8UC1, cv::Scalar(180)), Options(30), &corners));
}

TEST(Calibration, RecoversTheCameraThatRenderedTheImages) {
  test::TempDir dir;
  std::vector<std::string> paths = WriteViews(dir.path());
  paths.push_back(WriteBlank(dir.path()));
  // A board view of another size: padded by 20 x 10 pixels.
  cv::Mat padded;
  cv::copyMakeBorder(cv::imread(paths[0], cv::IMREAD_GRAYSCALE), padded, 0, 10, 0, 20, cv::BORDER_REPLICATE);
  paths.push_back((dir.path() / "padded.png").string());
  ASSERT_TRUE(cv::imwrite(paths.back(), padded));

  const CalibrationSummary summary = CalibrateFromImages(paths, Options(30));
  const Camera& c = summary.camera;
  const Camera t = TrueCamera();
  std::printf("%s\n", summary.BriefReport().c_str());
  for (const CalibrationImage& image : summary.images) {
    if (image.used) {
      std::printf("  %-12s used, RMS %.4f px\n", fs::path(image.path).filename().c_str(), image.reprojection_rms_px);
    } else {
      std::printf("  %-12s rejected: %s\n", fs::path(image.path).filename().c_str(), image.rejected_because.c_str());
    }
  }
  std::printf("          %12s %12s\n", "recovered", "truth");
  std::printf("  fx      %12.4f %12.4f  (%+.3f%%)\n", c.fx, t.fx, 100 * (c.fx / t.fx - 1));
  std::printf("  fy      %12.4f %12.4f  (%+.3f%%)\n", c.fy, t.fy, 100 * (c.fy / t.fy - 1));
  std::printf("  cx      %12.4f %12.4f\n", c.cx, t.cx);
  std::printf("  cy      %12.4f %12.4f\n", c.cy, t.cy);
  const char* names[] = {"k1", "k2", "p1", "p2", "k3"};
  for (int i = 0; i < 5; ++i) std::printf("  %-7s %12.6f %12.6f\n", names[i], c.distortion[i], t.distortion[i]);

  ASSERT_EQ(summary.images.size(), static_cast<size_t>(kNumViews + 2));
  EXPECT_EQ(summary.NumUsed(), static_cast<int>(kNumViews));
  for (int v = 0; v < kNumViews; ++v) EXPECT_TRUE(summary.images[v].used) << v;
  const CalibrationImage& blank = summary.images[kNumViews];
  EXPECT_FALSE(blank.used);
  EXPECT_EQ(blank.rejected_because, "no 9x6 chessboard found");
  const CalibrationImage& other_size = summary.images.back();
  EXPECT_FALSE(other_size.used);
  EXPECT_EQ(other_size.rejected_because, "size 660x490 differs from the 640x480 of most images");

  EXPECT_EQ(c.width, 640);
  EXPECT_EQ(c.height, 480);
  EXPECT_LT(std::abs(c.fx / t.fx - 1), 0.005);
  EXPECT_LT(std::abs(c.fy / t.fy - 1), 0.005);
  EXPECT_LT(std::abs(c.cx - t.cx), 2.0);
  EXPECT_LT(std::abs(c.cy - t.cy), 2.0);
  EXPECT_LT(summary.rms_px, 0.2);
  ASSERT_EQ(c.distortion.size(), 5u);

  // The lens as a whole: where the recovered camera puts the rays of the true camera's
  // pixels, on a grid over the image. The corners found reach to about 75 px from the
  // image's corners; beyond them the recovered lens is an extrapolation.
  double worst_inside = 0, worst_anywhere = 0;
  for (int j = 0; j <= 48; ++j) {
    for (int i = 0; i <= 64; ++i) {
      const Eigen::Vector2d pixel(i * 639.0 / 64, j * 479.0 / 48);
      const Eigen::Vector3d ray = t.PixelRaysInWorld(pixel).col(0);
      const double error = (c.DistortToPixel(ray.head<2>() / ray.z()) - pixel).norm();
      worst_anywhere = std::max(worst_anywhere, error);
      if (pixel.x() >= 40 && pixel.y() >= 40 && pixel.x() <= 599 && pixel.y() <= 439)
        worst_inside = std::max(worst_inside, error);
    }
  }
  std::printf("  lens: the recovered camera maps the true rays at most %.3f px off over [40, 599] x [40, 439], "
              "%.3f px over the whole image\n", worst_inside, worst_anywhere);
  EXPECT_LT(worst_inside, 1.0);  // measured 0.57 px: the focal lengths' 0.07% at 300 px, the principal point

  // The board poses against the ones rendered.
  double worst_mm = 0, worst_deg = 0, sum_rms = 0;
  for (int v = 0; v < kNumViews; ++v) {
    const CalibrationImage& image = summary.images[v];
    const BoardPose truth = PoseOf(kViews[v], Board(30));
    worst_mm = std::max(worst_mm, (image.cam_from_board_translation_mm - truth.first_corner_in_world_mm).norm());
    worst_deg = std::max(worst_deg, Deg(Eigen::AngleAxisd(image.cam_from_board_rotation *
                                                          truth.world_from_board_rotation.transpose()).angle()));
    sum_rms += image.reprojection_rms_px * image.reprojection_rms_px * 54;
  }
  std::printf("  board poses: at most %.3f mm and %.4f degrees from the truth\n", worst_mm, worst_deg);
  EXPECT_LT(worst_mm, 3.0);
  EXPECT_LT(worst_deg, 0.3);
  // The per-view errors add up to OpenCV's overall RMS.
  EXPECT_NEAR(std::sqrt(sum_rms / (54 * kNumViews)), summary.rms_px, 1e-3);
}

TEST(Calibration, FewerThanThreeUsableImagesIsAnInputError) {
  test::TempDir dir;
  const std::vector<std::string> views = WriteViews(dir.path(), 2);
  const std::string blank = WriteBlank(dir.path());
  const std::string bad = dir.Write("bad.png", "not a PNG").string();
  const std::string missing = (dir.path() / "missing.png").string();
  test::ExpectInputError([&] { CalibrateFromImages({views[0], blank, views[1], bad, missing}, Options(30)); },
                         {dir.path().string() + ": 2 usable chessboard images of 5, at least 3 needed",
                          "blank.png (no 9x6 chessboard found)", "bad.png (not a readable image)",
                          "missing.png (no such file)"});
  test::ExpectInputError([&] { CalibrateFromImages({}, Options(30)); }, {"0 usable chessboard images of 0"});
  test::ExpectInputError([&] { CalibrateFromImages(views, Options(-1)); }, {"chessboard options", "square"});
}

// The board lying on the floor: world = (x_board, -z_board, y_board), first corner at the
// origin.
BoardPose OnTheFloor() {
  BoardPose pose;
  pose.world_from_board_rotation << 1, 0, 0,
                                    0, 0, -1,
                                    0, 1, 0;
  return pose;
}

// The true camera's intrinsics at `centre_mm`, looking at `target_mm`.
Camera PlacedCamera(const Eigen::Vector3d& centre_mm, const Eigen::Vector3d& target_mm) {
  Camera placed = LookAtCamera("floor", 640, 480, 500, centre_mm, target_mm);
  const Camera t = TrueCamera();
  placed.fx = t.fx;
  placed.fy = t.fy;
  placed.cx = t.cx;
  placed.cy = t.cy;
  placed.distortion = t.distortion;
  return placed;
}

TEST(FloorPlacement, RecoversTheCameraThatSawTheBoard) {
  // A 7x4 board of 150 mm squares (1.2 m x 0.75 m with its margin) on the floor, seen by
  // the true camera 1.5 m up and 2 m away horizontally (2.5 m from the board's middle),
  // from four sides: OpenCV's first corner must be the board's corner (0, 0) from each.
  test::TempDir dir;
  SyntheticChessboardOptions board = Board(150);
  board.cols = 7;
  board.rows = 4;
  ChessboardOptions options = Options(150);
  options.cols = 7;
  options.rows = 4;
  const BoardPose pose = OnTheFloor();
  const Eigen::Vector3d middle = pose.CornerInWorld(3, 1.5, 150);
  double worst_mm = 0, worst_deg = 0;
  for (const double azimuth_deg : {-110.0, -20.0, 30.0, 135.0}) {
    const Eigen::Vector3d centre = middle + Eigen::Vector3d(2000 * std::sin(Rad(azimuth_deg)), 1500,
                                                            -2000 * std::cos(Rad(azimuth_deg)));
    const Camera truth = PlacedCamera(centre, middle);
    ASSERT_TRUE(SquaresInView(truth, board, pose)) << "test bug";
    const std::string path = (dir.path() / "floor.png").string();
    ASSERT_TRUE(cv::imwrite(path, Renderer().Render(truth, board, pose)));
    const FloorPlacement placement = PlaceCameraFromFloorBoard(TrueCamera(), path, options);
    const Eigen::Vector3d found = placement.camera.CentreInWorld();
    const double centre_error = (found - centre).norm();
    const double rotation_error = Deg(Eigen::AngleAxisd(placement.camera.cam_from_world_rotation *
                                                        truth.cam_from_world_rotation.transpose()).angle());
    std::printf("floor placement from (%.0f, %.0f, %.0f) mm: found (%.1f, %.1f, %.1f), centre off by %.2f mm, "
                "rotation by %.4f degrees, RMS %.3f px\n",
                centre.x(), centre.y(), centre.z(), found.x(), found.y(), found.z(), centre_error, rotation_error,
                placement.reprojection_rms_px);
    worst_mm = std::max(worst_mm, centre_error);
    worst_deg = std::max(worst_deg, rotation_error);
    EXPECT_LT(placement.reprojection_rms_px, 0.2);
    EXPECT_EQ(placement.camera.fx, TrueCamera().fx);
    std::string why;
    EXPECT_TRUE(placement.camera.Check(&why)) << why;
  }
  EXPECT_LT(worst_mm, 10.0);
  EXPECT_LT(worst_deg, 0.2);
}

TEST(FloorPlacement, Errors) {
  test::TempDir dir;
  const std::string blank = WriteBlank(dir.path());
  test::ExpectInputError([&] { PlaceCameraFromFloorBoard(TrueCamera(), blank, Options(100)); },
                         {blank, "no 9x6 chessboard found"});
  const std::string missing = (dir.path() / "missing.png").string();
  test::ExpectInputError([&] { PlaceCameraFromFloorBoard(TrueCamera(), missing, Options(100)); },
                         {missing, "no such file"});
  const std::string text = dir.Write("text.png", "not a PNG").string();
  test::ExpectInputError([&] { PlaceCameraFromFloorBoard(TrueCamera(), text, Options(100)); },
                         {text, "not a readable image"});
  const std::string small = (dir.path() / "small.png").string();
  ASSERT_TRUE(cv::imwrite(small, cv::Mat(240, 320, CV_8UC1, cv::Scalar(180))));
  test::ExpectInputError([&] { PlaceCameraFromFloorBoard(TrueCamera(), small, Options(100)); },
                         {small, "320x240", "640x480"});
  ChessboardOptions symmetric = Options(100);
  symmetric.cols = 8;
  test::ExpectInputError([&] { PlaceCameraFromFloorBoard(TrueCamera(), blank, symmetric); },
                         {"chessboard 8x6", "one odd and one even"});
}

}  // namespace
}  // namespace jgpm
