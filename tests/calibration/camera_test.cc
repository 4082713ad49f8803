// The camera model against OpenCV (cv::projectPoints is the projection oracle), the
// inverse rays against the projection, and the YAML files OpenCV's calibration sample
// writes.
#include "calibration/camera.h"

#include <cmath>
#include <limits>
#include <random>

#include <Eigen/Geometry>
#include <gtest/gtest.h>
#include <opencv2/calib3d.hpp>
#include <opencv2/core/eigen.hpp>

#include "io/base/error.h"
#include "test_support.h"

namespace jgpm {
namespace {

namespace fs = std::filesystem;

// One distortion of each length OpenCV knows: k1 k2 p1 p2 [k3 [k4 k5 k6]].
const std::vector<std::vector<double>> kDistortions = {
    {-0.21, 0.048, 0.0012, -0.0009},
    {-0.21, 0.048, 0.0012, -0.0009, 0.011},
    {-0.32, 0.11, 0.0012, -0.0009, 0.012, 0.08, -0.025, 0.006},  // rational model
};

Camera PosedCamera(const std::vector<double>& distortion) {
  Camera c;
  c.name = "test";
  c.width = 640;
  c.height = 480;
  c.fx = 523.5;
  c.fy = 519.25;
  c.cx = 325.75;
  c.cy = 236.5;
  c.distortion = distortion;
  c.cam_from_world_rotation =
      Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, -2, 0.5).normalized()).toRotationMatrix();
  c.cam_from_world_translation_mm = Eigen::Vector3d(120, -340, 2800);
  return c;
}

// World points in front of the camera whose undistorted image lies in [-0.65, 0.65] x
// [-0.5, 0.5] (normalised): the whole image and a little beyond for these lenses.
std::vector<Eigen::Vector3d> PointsInView(const Camera& c, int n, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> x(-0.65, 0.65), y(-0.5, 0.5), depth(300, 8000);
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < n; ++i) {
    const double z = depth(random);
    const Eigen::Vector3d in_camera(x(random) * z, y(random) * z, z);
    points.push_back(c.cam_from_world_rotation.transpose() * (in_camera - c.cam_from_world_translation_mm));
  }
  return points;
}

std::vector<cv::Point2d> OpenCvProject(const Camera& c, const std::vector<Eigen::Vector3d>& points) {
  std::vector<cv::Point3d> object;
  for (const Eigen::Vector3d& p : points) object.emplace_back(p.x(), p.y(), p.z());
  cv::Mat r, rvec, k;
  cv::eigen2cv(c.cam_from_world_rotation, r);
  cv::Rodrigues(r, rvec);
  const cv::Mat tvec = (cv::Mat_<double>(3, 1) << c.cam_from_world_translation_mm.x(),
                        c.cam_from_world_translation_mm.y(), c.cam_from_world_translation_mm.z());
  cv::eigen2cv(c.CameraMatrix(), k);
  std::vector<cv::Point2d> pixels;
  cv::projectPoints(object, rvec, tvec, k, cv::Mat(c.distortion, true), pixels);
  return pixels;
}

void ExpectPixelNear(const Eigen::Vector2d& ours, const cv::Point2d& oracle, const std::string& what) {
  EXPECT_NEAR(ours.x(), oracle.x, 1e-9 * std::max(1.0, std::abs(oracle.x))) << what;
  EXPECT_NEAR(ours.y(), oracle.y, 1e-9 * std::max(1.0, std::abs(oracle.y))) << what;
}

TEST(Camera, ProjectMatchesOpenCv) {
  for (const std::vector<double>& distortion : kDistortions) {
    const Camera c = PosedCamera(distortion);
    std::string why;
    ASSERT_TRUE(c.Check(&why)) << why;
    const std::vector<Eigen::Vector3d> points = PointsInView(c, 500, 1);
    const std::vector<cv::Point2d> oracle = OpenCvProject(c, points);
    for (size_t i = 0; i < points.size(); ++i) {
      Eigen::Vector2d pixel;
      ASSERT_TRUE(c.Project(points[i], &pixel));
      ExpectPixelNear(pixel, oracle[i], std::to_string(distortion.size()) + " coefficients, point " + std::to_string(i));
    }
  }
}

TEST(Camera, DistortToPixelMatchesOpenCv) {
  for (const std::vector<double>& distortion : kDistortions) {
    Camera c = PosedCamera(distortion);
    c.cam_from_world_rotation.setIdentity();
    c.cam_from_world_translation_mm.setZero();
    std::mt19937 random(2);
    std::uniform_real_distribution<double> x(-0.7, 0.7), y(-0.55, 0.55);
    std::vector<Eigen::Vector3d> points;
    for (int i = 0; i < 300; ++i) points.emplace_back(x(random), y(random), 1.0);
    const std::vector<cv::Point2d> oracle = OpenCvProject(c, points);
    for (size_t i = 0; i < points.size(); ++i) {
      ExpectPixelNear(c.DistortToPixel(points[i].head<2>()), oracle[i], std::to_string(distortion.size()) + " coefficients");
    }
  }
}

TEST(Camera, ProjectRefusesPointsBehindTheCamera) {
  const Camera c = PosedCamera(kDistortions[1]);
  Eigen::Vector2d pixel(-7, -7);
  const Eigen::Matrix3d world_from_cam = c.cam_from_world_rotation.transpose();
  for (double z : {-500.0, 0.0, 0.5}) {
    const Eigen::Vector3d p = world_from_cam * (Eigen::Vector3d(10, 20, z) - c.cam_from_world_translation_mm);
    EXPECT_FALSE(c.Project(p, &pixel)) << z;
    EXPECT_EQ(pixel, Eigen::Vector2d(-7, -7));
  }
}

double AngleRad(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b));
}

TEST(Camera, PixelRaysInvertProject) {
  for (const std::vector<double>& distortion : kDistortions) {
    const Camera c = PosedCamera(distortion);
    const std::vector<Eigen::Vector3d> points = PointsInView(c, 500, 3);
    Eigen::Matrix2Xd pixels(2, points.size());
    for (size_t i = 0; i < points.size(); ++i) {
      Eigen::Vector2d pixel;
      ASSERT_TRUE(c.Project(points[i], &pixel));
      pixels.col(i) = pixel;
    }
    const Eigen::Matrix3Xd rays = c.PixelRaysInWorld(pixels);
    double worst = 0;
    for (size_t i = 0; i < points.size(); ++i) {
      EXPECT_NEAR(rays.col(i).norm(), 1.0, 1e-12);
      worst = std::max(worst, AngleRad(rays.col(i), points[i] - c.CentreInWorld()));
    }
    EXPECT_LT(worst, 1e-6) << distortion.size() << " coefficients";
  }
}

TEST(Camera, PixelRaysThroughTheImageCornersReprojectThere) {
  // The strongest distortion is at the corners, where undistortion iterates longest.
  for (const std::vector<double>& distortion : kDistortions) {
    const Camera c = PosedCamera(distortion);
    Eigen::Matrix2Xd corners(2, 4);
    corners << 0, 639, 0, 639,
               0, 0, 479, 479;
    const Eigen::Matrix3Xd rays = c.PixelRaysInWorld(corners);
    for (int i = 0; i < 4; ++i) {
      Eigen::Vector2d pixel;
      ASSERT_TRUE(c.Project(c.CentreInWorld() + 3000 * rays.col(i), &pixel));
      EXPECT_LT((pixel - corners.col(i)).norm(), 1e-6) << distortion.size() << " coefficients, corner " << i;
    }
  }
  EXPECT_EQ(PosedCamera(kDistortions[0]).PixelRaysInWorld(Eigen::Matrix2Xd(2, 0)).cols(), 0);
}

TEST(Camera, LookAtPutsTheTargetAtThePrincipalPointWithWorldUpImageUp) {
  const Eigen::Vector3d centre(1000, 1500, -3000), target(200, 900, 500);
  const Camera c = LookAtCamera("look", 640, 480, 600, centre, target);
  std::string why;
  ASSERT_TRUE(c.Check(&why)) << why;
  EXPECT_LT((c.CentreInWorld() - centre).norm(), 1e-9);
  Eigen::Vector2d at_target, above, below;
  ASSERT_TRUE(c.Project(target, &at_target));
  EXPECT_NEAR(at_target.x(), 319.5, 1e-9);
  EXPECT_NEAR(at_target.y(), 239.5, 1e-9);
  // No roll: a point straight above the target is straight above it in the image.
  ASSERT_TRUE(c.Project(target + Eigen::Vector3d(0, 100, 0), &above));
  ASSERT_TRUE(c.Project(target - Eigen::Vector3d(0, 100, 0), &below));
  EXPECT_NEAR(above.x(), 319.5, 1e-9);
  EXPECT_LT(above.y(), 239.5 - 10);
  EXPECT_GT(below.y(), 239.5 + 10);
}

TEST(Camera, LookAtAlongZSeesWorldXOnTheLeft) {
  // Right-handed world, y up: looking along +z, +x is on the left of the picture.
  const Camera c = LookAtCamera("z", 640, 480, 500, Eigen::Vector3d::Zero(), Eigen::Vector3d(0, 0, 1000));
  Eigen::Vector2d plus_x;
  ASSERT_TRUE(c.Project(Eigen::Vector3d(100, 0, 1000), &plus_x));
  EXPECT_NEAR(plus_x.x(), 319.5 - 50, 1e-9);
  EXPECT_NEAR(plus_x.y(), 239.5, 1e-9);
}

TEST(Camera, CheckRejectsBadValues) {
  struct Case {
    std::string name;
    std::function<void(Camera*)> spoil;
    std::string phrase;
  };
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::vector<Case> cases = {
      {"zero width", [](Camera* c) { c->width = 0; }, "image size"},
      {"negative height", [](Camera* c) { c->height = -480; }, "image size"},
      {"zero fx", [](Camera* c) { c->fx = 0; }, "focal"},
      {"negative fy", [](Camera* c) { c->fy = -500; }, "focal"},
      {"nan cx", [&](Camera* c) { c->cx = nan; }, "non-finite"},
      {"inf fy", [](Camera* c) { c->fy = std::numeric_limits<double>::infinity(); }, "non-finite"},
      {"6 coefficients", [](Camera* c) { c->distortion.resize(6); }, "got 6"},
      {"no coefficients", [](Camera* c) { c->distortion.clear(); }, "got 0"},
      {"nan coefficient", [&](Camera* c) { c->distortion[2] = nan; }, "distortion"},
      {"nan translation", [&](Camera* c) { c->cam_from_world_translation_mm.y() = nan; }, "extrinsics"},
      {"scaled rotation", [](Camera* c) { c->cam_from_world_rotation *= 1.01; }, "not a rotation"},
      {"reflection", [](Camera* c) { c->cam_from_world_rotation.row(0) *= -1; }, "not a rotation"},
  };
  for (const Case& test : cases) {
    Camera c = PosedCamera(kDistortions[1]);
    std::string why;
    ASSERT_TRUE(c.Check(&why)) << why;
    test.spoil(&c);
    EXPECT_FALSE(c.Check(&why)) << test.name;
    EXPECT_NE(why.find(test.phrase), std::string::npos) << test.name << ": " << why;
    EXPECT_FALSE(c.Check(nullptr)) << test.name;
  }
}

void ExpectSameCamera(const Camera& a, const Camera& b) {
  EXPECT_EQ(a.name, b.name);
  EXPECT_EQ(a.width, b.width);
  EXPECT_EQ(a.height, b.height);
  EXPECT_EQ(a.fx, b.fx);
  EXPECT_EQ(a.fy, b.fy);
  EXPECT_EQ(a.cx, b.cx);
  EXPECT_EQ(a.cy, b.cy);
  EXPECT_EQ(a.distortion, b.distortion);
  EXPECT_EQ(a.cam_from_world_rotation, b.cam_from_world_rotation);
  EXPECT_EQ(a.cam_from_world_translation_mm, b.cam_from_world_translation_mm);
  EXPECT_EQ(a.clock_offset_s, b.clock_offset_s);
}

TEST(CameraYaml, FormatThenParseGivesIdenticalValues) {
  for (const std::vector<double>& distortion : kDistortions) {
    for (const std::string name : {"cam0", "left-camera_1.b", "0"}) {
      CameraFile file;
      file.camera = PosedCamera(distortion);
      file.camera.name = name;
      file.camera.fx = 523.123456789012345;  // needs all 17 digits
      file.has_extrinsics = true;
      file.avg_reprojection_error_px = 0.0412345678901234;
      file.camera.clock_offset_s = name == "0" ? 0 : -0.4333333333333333;  // written only when not 0
      const CameraFile back = ParseCameraYaml(FormatCameraYaml(file), "memory");
      ExpectSameCamera(back.camera, file.camera);
      EXPECT_TRUE(back.has_extrinsics);
      EXPECT_EQ(back.avg_reprojection_error_px, file.avg_reprojection_error_px);
    }
  }
}

TEST(CameraYaml, WriteThenReadFromDisk) {
  test::TempDir dir;
  CameraFile file;
  file.camera = PosedCamera(kDistortions[2]);
  file.has_extrinsics = true;
  const fs::path path = dir.path() / "cam.yaml";
  WriteCameraYaml(file, path.string());
  const CameraFile back = ReadCameraYaml(path.string());
  ExpectSameCamera(back.camera, file.camera);
  // An unplaced camera is written without a pose and reads back unplaced.
  CameraFile unplaced = file;
  unplaced.has_extrinsics = false;
  const CameraFile back_unplaced = ParseCameraYaml(FormatCameraYaml(unplaced), "unplaced");
  EXPECT_FALSE(back_unplaced.has_extrinsics);
  EXPECT_EQ(back_unplaced.camera.cam_from_world_rotation, Eigen::Matrix3d::Identity());
  EXPECT_LT(back.avg_reprojection_error_px, 0);  // none written
  // The pose alone reads back from a camera file too.
  const CameraPose pose = ReadCameraPoseYaml(path.string());
  EXPECT_EQ(pose.cam_from_world_rotation, file.camera.cam_from_world_rotation);
  EXPECT_EQ(pose.cam_from_world_translation_mm, file.camera.cam_from_world_translation_mm);
}

TEST(CameraYaml, ReadsTheFileOpenCvsCalibrationSampleWrites) {
  // The keys, types and order of samples/cpp/calibration.cpp's saveCameraParams, written
  // by OpenCV itself.
  test::TempDir dir;
  const fs::path path = dir.path() / "out_camera_data.yml";
  const cv::Mat k = (cv::Mat_<double>(3, 3) << 531.25, 0, 318.75, 0, 529.5, 244.125, 0, 0, 1);
  const cv::Mat d = (cv::Mat_<double>(5, 1) << -0.25, 0.0625, 0.001, -0.002, 0.0);
  {
    cv::FileStorage out(path.string(), cv::FileStorage::WRITE);
    out << "calibration_time" << "Fri Nov 20 10:00:00 2026";
    out << "nframes" << 3;
    out << "image_width" << 640;
    out << "image_height" << 480;
    out << "board_width" << 9;
    out << "board_height" << 6;
    out << "square_size" << 25.0f;
    out.writeComment("flags: +fix_k4 +fix_k5", false);
    out << "flags" << 6144;
    out << "camera_matrix" << k;
    out << "distortion_coefficients" << d;
    out << "avg_reprojection_error" << 0.21875;
    out << "per_view_reprojection_errors" << cv::Mat(std::vector<float>{0.2f, 0.25f, 0.19f});
    out.writeComment("a set of 6-tuples (rotation vector + translation vector) for each view", false);
    cv::Mat extrinsics(3, 6, CV_64F, cv::Scalar(0.5));
    out << "extrinsic_parameters" << extrinsics;
  }
  const CameraFile file = ReadCameraYaml(path.string());
  EXPECT_FALSE(file.has_extrinsics);
  EXPECT_EQ(file.avg_reprojection_error_px, 0.21875);
  const Camera& c = file.camera;
  EXPECT_EQ(c.width, 640);
  EXPECT_EQ(c.height, 480);
  EXPECT_EQ(c.fx, 531.25);
  EXPECT_EQ(c.fy, 529.5);
  EXPECT_EQ(c.cx, 318.75);
  EXPECT_EQ(c.cy, 244.125);
  EXPECT_EQ(c.distortion, (std::vector<double>{-0.25, 0.0625, 0.001, -0.002, 0.0}));
  EXPECT_EQ(c.cam_from_world_rotation, Eigen::Matrix3d::Identity());
  EXPECT_EQ(c.cam_from_world_translation_mm, Eigen::Vector3d::Zero());
  EXPECT_EQ(c.name, "cam0");
  // The sample's file has no pose.
  test::ExpectInputError([&] { ReadCameraPoseYaml(path.string()); },
                         {path.string(), "cam_from_world_rotation", "cam_from_world_translation_mm"});
}

// A valid camera file written by hand, as a person would edit one.
const char kValidYaml[] = R"(%YAML:1.0
---
camera_name: "cam0"
image_width: 640
image_height: 480
camera_matrix: !!opencv-matrix
   rows: 3
   cols: 3
   dt: d
   data: [ 520., 0., 320., 0., 520., 240., 0., 0., 1. ]
distortion_coefficients: !!opencv-matrix
   rows: 1
   cols: 5
   dt: d
   data: [ -0.2, 0.05, 0.001, -0.001, 0. ]
cam_from_world_rotation: !!opencv-matrix
   rows: 3
   cols: 3
   dt: d
   data: [ 1., 0., 0., 0., 1., 0., 0., 0., 1. ]
cam_from_world_translation_mm: !!opencv-matrix
   rows: 3
   cols: 1
   dt: d
   data: [ 0., -1500., 3000. ]
)";

const char kRotationBlock[] = R"(cam_from_world_rotation: !!opencv-matrix
   rows: 3
   cols: 3
   dt: d
   data: [ 1., 0., 0., 0., 1., 0., 0., 0., 1. ]
)";
const char kTranslationBlock[] = R"(cam_from_world_translation_mm: !!opencv-matrix
   rows: 3
   cols: 1
   dt: d
   data: [ 0., -1500., 3000. ]
)";

TEST(CameraYaml, TheHandWrittenFileIsValid) {
  test::TempDir dir;
  const CameraFile file = ReadCameraYaml(dir.Write("cam.yaml", kValidYaml).string());
  EXPECT_TRUE(file.has_extrinsics);
  EXPECT_EQ(file.camera.cam_from_world_translation_mm, Eigen::Vector3d(0, -1500, 3000));
  EXPECT_EQ(file.camera.distortion.size(), 5u);
  // A file with only the pose keys is a valid pose file, not a valid camera file.
  const fs::path pose_path = dir.Write("pose.yaml", std::string("%YAML:1.0\n---\n") + kRotationBlock + kTranslationBlock);
  EXPECT_EQ(ReadCameraPoseYaml(pose_path.string()).cam_from_world_translation_mm, Eigen::Vector3d(0, -1500, 3000));
  test::ExpectInputError([&] { ReadCameraYaml(pose_path.string()); }, {pose_path.string(), "camera_matrix"});
}

// Each malformed file names the file and the key (or, for text that is no YAML, says so).
class MalformedCameraYaml : public testing::TestWithParam<test::MalformedCase> {};

TEST_P(MalformedCameraYaml, NamesTheFileAndTheKey) {
  const test::MalformedCase& c = GetParam();
  test::TempDir dir;
  const std::string text = c.from == "*" ? c.to : test::Replace(kValidYaml, c.from, c.to);
  const fs::path path = dir.Write("cam.yaml", text);
  test::ExpectInputError([&] { ReadCameraYaml(path.string()); }, {path.string() + ":", c.phrase});
}

const test::MalformedCase kMalformed[] = {
    {"MissingCameraMatrix", "camera_matrix:", "camera_matrx:", "", "missing key 'camera_matrix'"},
    {"CameraMatrix2x3", "   rows: 3\n   cols: 3\n   dt: d\n   data: [ 520., 0., 320., 0., 520., 240., 0., 0., 1. ]",
     "   rows: 2\n   cols: 3\n   dt: d\n   data: [ 520., 0., 320., 0., 520., 240. ]", "", "'camera_matrix' is 2x3"},
    {"CameraMatrixWithSkew", "520., 0., 320.,", "520., 3., 320.,", "", "'camera_matrix' must be [fx 0 cx"},
    {"CameraMatrixNotAMatrix", "camera_matrix: !!opencv-matrix\n   rows: 3\n   cols: 3\n   dt: d\n   data: [ 520., 0., 320., 0., 520., 240., 0., 0., 1. ]",
     "camera_matrix: 520", "", "'camera_matrix' is not a 3x3"},
    {"NegativeFocalLength", "0., 520., 240.,", "0., -520., 240.,", "", "'camera_matrix': focal"},
    {"StringImageWidth", "image_width: 640", "image_width: \"640\"", "", "'image_width' must be a positive integer"},
    {"ZeroImageHeight", "image_height: 480", "image_height: 0", "", "'image_height' must be a positive integer"},
    {"MissingImageHeight", "image_height: 480", "image_heigth: 480", "", "missing key 'image_height'"},
    {"NanInDistortion", "[ -0.2, 0.05,", "[ .Nan, 0.05,", "", "'distortion_coefficients' holds a non-finite"},
    {"InfInDistortion", "[ -0.2, 0.05,", "[ -.Inf, 0.05,", "", "'distortion_coefficients' holds a non-finite"},
    {"SixDistortionCoefficients", "cols: 5\n   dt: d\n   data: [ -0.2, 0.05, 0.001, -0.001, 0. ]",
     "cols: 6\n   dt: d\n   data: [ -0.2, 0.05, 0.001, -0.001, 0., 0. ]", "", "'distortion_coefficients': expected 4, 5 or 8"},
    {"DistortionMatrix2x3", "rows: 1\n   cols: 5\n   dt: d\n   data: [ -0.2, 0.05, 0.001, -0.001, 0. ]",
     "rows: 2\n   cols: 3\n   dt: d\n   data: [ -0.2, 0.05, 0.001, -0.001, 0., 0. ]", "", "'distortion_coefficients' is 2x3"},
    {"CameraNameNotAString", "camera_name: \"cam0\"", "camera_name: 7", "", "'camera_name' must be a string"},
    {"CameraNameIsAPath", "camera_name: \"cam0\"", "camera_name: \"../cam0\"", "", "'camera_name' must be 1-64"},
    // Found by the fuzzer: a name OpenCV reads but cannot write back.
    {"CameraNameStartsWithABracket", "camera_name: \"cam0\"", "camera_name:]\xa6\xa6", "", "'camera_name' must be 1-64"},
    {"RotationNotARotation", "[ 1., 0., 0., 0., 1., 0., 0., 0., 1. ]", "[ 1., 0., 0., 0., 2., 0., 0., 0., 1. ]", "",
     "'cam_from_world_rotation': cam_from_world_rotation is not a rotation"},
    {"RotationIsAReflection", "[ 1., 0., 0., 0., 1., 0., 0., 0., 1. ]", "[ -1., 0., 0., 0., 1., 0., 0., 0., 1. ]", "",
     "is not a rotation"},
    {"Translation1x2", "   rows: 3\n   cols: 1\n   dt: d\n   data: [ 0., -1500., 3000. ]",
     "   rows: 1\n   cols: 2\n   dt: d\n   data: [ 0., -1500. ]", "", "'cam_from_world_translation_mm' is 1x2"},
    {"OnlyTheRotation", kTranslationBlock, "", "", "missing key 'cam_from_world_translation_mm'"},
    {"OnlyTheTranslation", kRotationBlock, "", "", "missing key 'cam_from_world_rotation'"},
    {"ClockOffsetNotANumber", "camera_name: \"cam0\"", "camera_name: \"cam0\"\nclock_offset_s: \"late\"", "",
     "'clock_offset_s' must be a number"},
    {"ClockOffsetNan", "camera_name: \"cam0\"", "camera_name: \"cam0\"\nclock_offset_s: .Nan", "",
     "'clock_offset_s': clock offset not finite"},
    {"NotYaml", "*", "this is {not [ yaml: at all\n", "", "not an OpenCV YAML file"},
    {"YamlButNotAMap", "*", "%YAML:1.0\n---\n- 1\n- 2\n", "", "not an OpenCV YAML file"},
    // Found by tests/fuzz/camera_yaml_fuzzer: OpenCV allocated rows x cols before reading
    // the data, and ended the process on an empty nested key.
    {"GarbledColumnCount", "   cols: 3\n   dt: d\n   data: [ 520.", "   cols: 3000000000\n   dt: d\n   data: [ 520.", "",
     "'camera_matrix' is not a 3x3 opencv-matrix (rows, cols and as many data values)"},
    {"ColumnCountNotANumber", "   cols: 3\n   dt: d\n   data: [ 520.", "   cols:A3\n   dt: d\n   data: [ 520.", "",
     "'camera_matrix' is not a 3x3"},
    {"EmptyNestedKey", "   dt: d\n   data: [ 520.", "   :1.0dt: d\n   data: [ 520.", "", "a key is empty"},
    // Found by the fuzzer too: OpenCV looped forever on a '-' line after the first document
    // had ended (these cases hang without the check in OpenYaml).
    {"DashAfterDocumentEnd", "*", "%YAML:1.0\na: 1\n...\n-a\n", "", "a document end '...'"},
    {"DashAfterIndentedFirstKey", "*", "%YAML:1.0\n a: 1\nxyz\n-\n", "", "the first key is indented"},
    {"KeyOnTheDocumentStartLine", "*", "%YAML:1.0\n--- a: 1\nxyz\n-\n", "", "text after '---'"},
    {"SecondDocument", "*", "%YAML:1.0\n---\na: 1\n---\nb: 2\n", "", "a second YAML document"},
    {"DeleteByte", "*", "%YAML:1.0\na: 1\x7f\n", "", "control byte 127"},
    {"Empty", "*", "", "", "empty"},
    {"OnlyBlanks", "*", "\n   \n", "", "file is empty"},
};
INSTANTIATE_TEST_SUITE_P(Cases, MalformedCameraYaml, testing::ValuesIn(kMalformed), test::CaseName);

TEST(CameraYaml, ParseFromMemoryNamesTheSource) {
  test::ExpectInputError([] { ParseCameraYaml("", "source.yaml"); }, {"source.yaml", "not an OpenCV YAML file"});
  test::ExpectInputError([] { ParseCameraPoseYaml(kValidYaml + std::string("garbage: [ 1, "), "p.yaml"); },
                         {"p.yaml", "not an OpenCV YAML file"});
}

TEST(CameraYaml, PoseFileErrors) {
  test::TempDir dir;
  const fs::path only_rotation = dir.Write("r.yaml", std::string("%YAML:1.0\n---\n") + kRotationBlock);
  test::ExpectInputError([&] { ReadCameraPoseYaml(only_rotation.string()); },
                         {only_rotation.string(), "missing key 'cam_from_world_translation_mm'"});
  const fs::path bent = dir.Write("bent.yaml", test::Replace(kValidYaml, "[ 1., 0., 0., 0., 1., 0., 0., 0., 1. ]",
                                                             "[ 1., 0.1, 0., 0., 1., 0., 0., 0., 1. ]"));
  test::ExpectInputError([&] { ReadCameraPoseYaml(bent.string()); },
                         {bent.string(), "'cam_from_world_rotation' is not a rotation"});
  test::ExpectInputError([&] { ReadCameraPoseYaml((dir.path() / "missing.yaml").string()); }, {"missing.yaml"});
}

}  // namespace
}  // namespace jgpm
