#include "calibration/camera.h"

#include <cctype>
#include <cmath>
#include <string>
#include <string_view>

#include <Eigen/Geometry>
#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>
#include <opencv2/core/eigen.hpp>

#include "io/base/error.h"
#include "io/base/text_reader.h"

namespace jgpm {
namespace {

bool IsRotation(const Eigen::Matrix3d& r) {
  return (r.transpose() * r - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() <= 1e-6 &&
         std::abs(r.determinant() - 1) <= 1e-6;
}

}  // namespace

bool Camera::Check(std::string* why) const {
  auto fail = [&](const std::string& what) {
    if (why) *why = what;
    return false;
  };
  if (width <= 0 || height <= 0) return fail("image size must be positive");
  if (!(std::isfinite(fx) && std::isfinite(fy) && std::isfinite(cx) && std::isfinite(cy)))
    return fail("camera matrix has a non-finite value");
  if (fx <= 0 || fy <= 0) return fail("focal lengths must be positive");
  if (distortion.size() != 4 && distortion.size() != 5 && distortion.size() != 8)
    return fail("expected 4, 5 or 8 distortion coefficients (k1 k2 p1 p2 [k3 [k4 k5 k6]]), got " +
                std::to_string(distortion.size()));
  for (double d : distortion)
    if (!std::isfinite(d)) return fail("distortion coefficient not finite");
  if (!std::isfinite(clock_offset_s)) return fail("clock offset not finite");
  if (!cam_from_world_rotation.allFinite() || !cam_from_world_translation_mm.allFinite())
    return fail("extrinsics have a non-finite value");
  if (!IsRotation(cam_from_world_rotation))
    return fail("cam_from_world_rotation is not a rotation (orthonormal, determinant +1)");
  return true;
}

Eigen::Matrix3d Camera::CameraMatrix() const {
  Eigen::Matrix3d k;
  k << fx, 0, cx, 0, fy, cy, 0, 0, 1;
  return k;
}

Eigen::Vector3d Camera::CentreInWorld() const {
  return -cam_from_world_rotation.transpose() * cam_from_world_translation_mm;
}

Eigen::Vector2d Camera::DistortToPixel(const Eigen::Vector2d& normalised) const {
  const double x = normalised.x(), y = normalised.y();
  const double r2 = x * x + y * y;
  auto k = [&](size_t i) { return i < distortion.size() ? distortion[i] : 0.0; };
  const double radial = (1 + r2 * (k(0) + r2 * (k(1) + r2 * k(4)))) /
                        (1 + r2 * (k(5) + r2 * (k(6) + r2 * k(7))));
  const double xd = x * radial + 2 * k(2) * x * y + k(3) * (r2 + 2 * x * x);
  const double yd = y * radial + k(2) * (r2 + 2 * y * y) + 2 * k(3) * x * y;
  return {fx * xd + cx, fy * yd + cy};
}

bool Camera::Project(const Eigen::Vector3d& point_in_world_mm, Eigen::Vector2d* pixel) const {
  const Eigen::Vector3d p = ToCamera(point_in_world_mm);
  if (p.z() <= 1.0) return false;
  *pixel = DistortToPixel(p.head<2>() / p.z());
  return true;
}

Eigen::Matrix3Xd Camera::PixelRaysInWorld(const Eigen::Matrix2Xd& pixels) const {
  const int n = static_cast<int>(pixels.cols());
  Eigen::Matrix3Xd rays(3, n);
  if (n == 0) return rays;
  cv::Mat in(n, 1, CV_64FC2), out;
  for (int i = 0; i < n; ++i) in.at<cv::Vec2d>(i) = cv::Vec2d(pixels(0, i), pixels(1, i));
  cv::Mat k, d(1, static_cast<int>(distortion.size()), CV_64F);
  cv::eigen2cv(CameraMatrix(), k);
  for (size_t i = 0; i < distortion.size(); ++i) d.at<double>(static_cast<int>(i)) = distortion[i];
  // The default 5 iterations leave ~0.1 px at the corners of a strongly distorted lens.
  cv::undistortPoints(in, out, k, d, cv::noArray(), cv::noArray(),
                      cv::TermCriteria(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 100, 1e-12));
  const Eigen::Matrix3d world_from_cam = cam_from_world_rotation.transpose();
  for (int i = 0; i < n; ++i) {
    const cv::Vec2d q = out.at<cv::Vec2d>(i);
    rays.col(i) = (world_from_cam * Eigen::Vector3d(q[0], q[1], 1)).normalized();
  }
  return rays;
}

Camera LookAtCamera(const std::string& name, int width, int height, double focal_px,
                    const Eigen::Vector3d& centre_mm, const Eigen::Vector3d& target_mm) {
  const Eigen::Vector3d forward = (target_mm - centre_mm).normalized();
  // Image x to the right of the view, image y down (world -y projected).
  const Eigen::Vector3d right = forward.cross(Eigen::Vector3d::UnitY()).normalized();
  JGPM_CHECK(right.allFinite());
  const Eigen::Vector3d down = forward.cross(right);
  Camera camera;
  camera.name = name;
  camera.width = width;
  camera.height = height;
  camera.fx = camera.fy = focal_px;
  camera.cx = (width - 1) / 2.0;
  camera.cy = (height - 1) / 2.0;
  camera.cam_from_world_rotation.row(0) = right;
  camera.cam_from_world_rotation.row(1) = down;
  camera.cam_from_world_rotation.row(2) = forward;
  camera.cam_from_world_translation_mm = -camera.cam_from_world_rotation * centre_mm;
  return camera;
}

namespace {

// A matrix node of the expected shape (either orientation for vectors), finite.
cv::Mat ReadMatrix(const cv::FileNode& node, const std::string& key, int rows, int cols,
                   const std::string& source, bool vector_any_length = false) {
  const std::string expected =
      vector_any_length ? "a 1xN or Nx1 opencv-matrix"
                        : "a " + std::to_string(rows) + "x" + std::to_string(cols) + " opencv-matrix";
  if (node.empty() || node.isNone())
    ThrowInputError(source, "missing key '" + key + "' (" + expected + ")");
  // OpenCV allocates rows x cols before reading the data: check the header first, so a
  // garbled size cannot ask for gigabytes.
  constexpr int kMaxSide = 16;
  if (!node.isMap()) ThrowInputError(source, "key '" + key + "' is not " + expected);
  const cv::FileNode r = node["rows"], c = node["cols"], values = node["data"];
  if (!r.isInt() || !c.isInt() || !values.isSeq() || static_cast<int>(r) < 1 ||
      static_cast<int>(c) < 1 || static_cast<int>(r) > kMaxSide || static_cast<int>(c) > kMaxSide ||
      values.size() != static_cast<size_t>(static_cast<int>(r) * static_cast<int>(c)))
    ThrowInputError(source, "key '" + key + "' is not " + expected +
                                " (rows, cols and as many data values)");
  cv::Mat m;
  try {
    node >> m;
  } catch (const cv::Exception&) {
    m.release();
  }
  if (m.empty() || m.channels() != 1)
    ThrowInputError(source, "key '" + key + "' is not " + expected);
  m.convertTo(m, CV_64F);
  const bool is_vector = m.rows == 1 || m.cols == 1;
  const bool shape_ok = vector_any_length ? is_vector
                        : (m.rows == rows && m.cols == cols) ||
                              (cols == 1 && m.rows == 1 && m.cols == rows);
  if (!shape_ok)
    ThrowInputError(source, "key '" + key + "' is " + std::to_string(m.rows) + "x" +
                                std::to_string(m.cols) + ", expected " + expected);
  if (!cv::checkRange(m))
    ThrowInputError(source, "key '" + key + "' holds a non-finite number");
  return m;
}

int ReadPositiveInt(const cv::FileNode& node, const std::string& key, const std::string& source) {
  if (node.empty() || node.isNone())
    ThrowInputError(source, "missing key '" + key + "' (a positive integer)");
  if (!node.isInt() || static_cast<int>(node) <= 0)
    ThrowInputError(source, "key '" + key + "' must be a positive integer");
  return static_cast<int>(node);
}

}  // namespace

bool ValidCameraName(const std::string& name) {
  if (name.empty() || name.size() > 64 || !std::isalnum(static_cast<unsigned char>(name[0]))) return false;
  for (const char ch : name)
    if (!std::isalnum(static_cast<unsigned char>(ch)) && ch != '_' && ch != '-' && ch != '.') return false;
  return true;
}

namespace {

cv::FileStorage OpenYaml(const std::string& text, const std::string& source) {
  // OpenCV 4.6's YAML reader ends the process (an exception thrown through a noexcept
  // frame) on control bytes and on an indented line starting with ':' (an empty key), and
  // loops forever on a line starting with '-' after its first document has ended (at a
  // '...' line, or at a line indented less than an indented first key); found by fuzzing.
  // None of these belongs in a camera file, which is one document whose keys start in the
  // first column, so refuse them first.
  int line = 1;
  bool line_start = true;
  bool seen_content = false;  // a line other than blanks, comments, directives, '---'
  for (size_t i = 0; i < text.size(); ++i) {
    const unsigned char ch = static_cast<unsigned char>(text[i]);
    const std::string where = source + ":" + std::to_string(line);
    if ((ch < 0x20 && ch != '\n' && ch != '\r' && ch != '\t') || ch == 0x7f)
      ThrowInputError(where, "not a text file (control byte " + std::to_string(ch) + ")");
    if (ch == ':' && line_start) ThrowInputError(where, "a key is empty");
    if (i == 0 || text[i - 1] == '\n') {  // the line's first character
      const std::string_view rest = std::string_view(text).substr(i, text.find('\n', i) - i);
      const size_t first = rest.find_first_not_of(" \t\r");
      const bool blank = first == std::string_view::npos || rest[first] == '#' || rest[first] == '%';
      if (rest.substr(0, 3) == "...")
        ThrowInputError(where, "a document end '...' (a camera file is one YAML document)");
      if (rest.substr(0, 3) == "---") {
        if (seen_content) ThrowInputError(where, "a second YAML document '---' (a camera file is one document)");
        const size_t after = rest.find_first_not_of(" \t\r", 3);
        if (after != std::string_view::npos && rest[after] != '#')
          ThrowInputError(where, "text after '---' (the keys start on the next line)");
      } else if (!blank) {
        if (!seen_content && first != 0) ThrowInputError(where, "the first key is indented (expected it in column 1)");
        seen_content = true;
      }
    }
    if (ch == '\n') ++line;
    line_start = ch == '\n' || (line_start && (ch == ' ' || ch == '\t'));
  }
  cv::FileStorage fs;
  try {
    fs.open(text, cv::FileStorage::READ | cv::FileStorage::MEMORY | cv::FileStorage::FORMAT_YAML);
  } catch (const cv::Exception& e) {
    ThrowInputError(source, "not an OpenCV YAML file (" + e.msg + ")");
  }
  if (!fs.isOpened() || !fs.root().isMap())
    ThrowInputError(source, "not an OpenCV YAML file (expected a map starting with %YAML:1.0)");
  return fs;
}

// Reads both extrinsics keys into `pose`; false when neither is there.
bool ReadExtrinsics(const cv::FileStorage& fs, const std::string& source, CameraPose* pose) {
  const cv::FileNode rotation = fs["cam_from_world_rotation"];
  const cv::FileNode translation = fs["cam_from_world_translation_mm"];
  const bool has_r = !rotation.empty() && !rotation.isNone();
  const bool has_t = !translation.empty() && !translation.isNone();
  if (has_r != has_t)
    ThrowInputError(source, std::string("missing key '") +
                                (has_r ? "cam_from_world_translation_mm" : "cam_from_world_rotation") +
                                "' (the extrinsics need both keys)");
  if (!has_r) return false;
  cv::cv2eigen(ReadMatrix(rotation, "cam_from_world_rotation", 3, 3, source), pose->cam_from_world_rotation);
  const cv::Mat t = ReadMatrix(translation, "cam_from_world_translation_mm", 3, 1, source);
  for (int i = 0; i < 3; ++i) pose->cam_from_world_translation_mm[i] = t.at<double>(i);
  return true;
}

}  // namespace

CameraFile ParseCameraYaml(const std::string& text, const std::string& source) {
  const cv::FileStorage fs = OpenYaml(text, source);
  CameraFile file;
  Camera& c = file.camera;
  const cv::Mat k = ReadMatrix(fs["camera_matrix"], "camera_matrix", 3, 3, source);
  if (k.at<double>(0, 1) != 0 || k.at<double>(1, 0) != 0 || k.at<double>(2, 0) != 0 ||
      k.at<double>(2, 1) != 0 || k.at<double>(2, 2) != 1)
    ThrowInputError(source, "key 'camera_matrix' must be [fx 0 cx; 0 fy cy; 0 0 1]");
  c.fx = k.at<double>(0, 0);
  c.fy = k.at<double>(1, 1);
  c.cx = k.at<double>(0, 2);
  c.cy = k.at<double>(1, 2);
  const cv::Mat d = ReadMatrix(fs["distortion_coefficients"], "distortion_coefficients", 0, 0,
                               source, /*vector_any_length=*/true);
  c.distortion.assign(d.begin<double>(), d.end<double>());
  c.width = ReadPositiveInt(fs["image_width"], "image_width", source);
  c.height = ReadPositiveInt(fs["image_height"], "image_height", source);
  const cv::FileNode name = fs["camera_name"];
  if (!name.empty() && !name.isNone()) {
    if (!name.isString()) ThrowInputError(source, "key 'camera_name' must be a string");
    c.name = static_cast<std::string>(name);
    if (!ValidCameraName(c.name))
      ThrowInputError(source, "key 'camera_name' must be 1-64 letters, digits, '_', '-' or '.' (it names files)");
  }
  CameraPose pose;
  if (ReadExtrinsics(fs, source, &pose)) {
    c.cam_from_world_rotation = pose.cam_from_world_rotation;
    c.cam_from_world_translation_mm = pose.cam_from_world_translation_mm;
    file.has_extrinsics = true;
  }
  const cv::FileNode offset = fs["clock_offset_s"];
  if (!offset.empty() && !offset.isNone()) {
    if (!offset.isReal() && !offset.isInt()) ThrowInputError(source, "key 'clock_offset_s' must be a number (seconds)");
    c.clock_offset_s = static_cast<double>(offset);
  }
  const cv::FileNode error = fs["avg_reprojection_error"];
  if (error.isReal() || error.isInt()) file.avg_reprojection_error_px = static_cast<double>(error);
  std::string why;
  if (!c.Check(&why)) {
    // Name the key the reason is about.
    std::string key = "camera_matrix";
    if (why.find("distortion") != std::string::npos) key = "distortion_coefficients";
    if (why.find("rotation") != std::string::npos) key = "cam_from_world_rotation";
    if (why.find("clock") != std::string::npos) key = "clock_offset_s";
    ThrowInputError(source, "key '" + key + "': " + why);
  }
  return file;
}

CameraFile ReadCameraYaml(const std::string& path) {
  return ParseCameraYaml(ReadTextFile(path, "a camera YAML file"), path);
}

std::string FormatCameraYaml(const CameraFile& file) {
  const Camera& c = file.camera;
  std::string why;
  JGPM_CHECK(c.Check(&why));
  cv::FileStorage fs("camera.yaml", cv::FileStorage::WRITE | cv::FileStorage::MEMORY |
                                        cv::FileStorage::FORMAT_YAML);
  fs << "camera_name" << c.name;
  fs << "image_width" << c.width << "image_height" << c.height;
  cv::Mat k, r;
  cv::eigen2cv(c.CameraMatrix(), k);
  fs << "camera_matrix" << k;
  fs << "distortion_coefficients" << cv::Mat(c.distortion, true).reshape(1, 1);
  if (file.has_extrinsics) {
    cv::eigen2cv(c.cam_from_world_rotation, r);
    fs << "cam_from_world_rotation" << r;
    fs << "cam_from_world_translation_mm"
       << cv::Mat(cv::Vec3d(c.cam_from_world_translation_mm.data()));
  }
  if (c.clock_offset_s != 0) fs << "clock_offset_s" << c.clock_offset_s;
  if (file.avg_reprojection_error_px >= 0)
    fs << "avg_reprojection_error" << file.avg_reprojection_error_px;
  return fs.releaseAndGetString();
}

void WriteCameraYaml(const CameraFile& file, const std::string& path) {
  WriteFileAtomic(path, FormatCameraYaml(file));
}

CameraPose ParseCameraPoseYaml(const std::string& text, const std::string& source) {
  const cv::FileStorage fs = OpenYaml(text, source);
  CameraPose pose;
  if (!ReadExtrinsics(fs, source, &pose))
    ThrowInputError(source, "missing keys 'cam_from_world_rotation' (3x3) and 'cam_from_world_translation_mm' (3x1)");
  if (!IsRotation(pose.cam_from_world_rotation))
    ThrowInputError(source, "key 'cam_from_world_rotation' is not a rotation (orthonormal, determinant +1)");
  return pose;
}

CameraPose ReadCameraPoseYaml(const std::string& path) {
  return ParseCameraPoseYaml(ReadTextFile(path, "a camera pose YAML file"), path);
}

}  // namespace jgpm
