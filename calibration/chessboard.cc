#include "calibration/chessboard.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <limits>
#include <map>

#include <opencv2/calib3d.hpp>
#include <opencv2/core/eigen.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "io/base/error.h"
#include "io/base/text_reader.h"

namespace jgpm {
namespace {

std::string BoardName(const ChessboardOptions& o) {
  return std::to_string(o.cols) + "x" + std::to_string(o.rows);
}

std::string SizeName(int width, int height) {
  return std::to_string(width) + "x" + std::to_string(height);
}

// The folder all the images are in (for error messages), or a description.
std::string ImagesWhere(const std::vector<std::string>& paths) {
  if (paths.empty()) return "chessboard images";
  const std::filesystem::path folder = std::filesystem::path(paths[0]).parent_path();
  for (const std::string& path : paths) {
    if (std::filesystem::path(path).parent_path() != folder) return "chessboard images";
  }
  return folder.empty() ? std::string("chessboard images") : folder.string();
}

// Grey image, or empty when the file is not a readable image. (A missing file is caught
// first: cv::imread would print a warning of its own.)
cv::Mat ReadGrey(const std::string& path) {
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error)) return cv::Mat();
  try {
    return cv::imread(path, cv::IMREAD_GRAYSCALE);
  } catch (const cv::Exception&) {
    return cv::Mat();
  }
}

// Inner corner (i, j) at (i s, j s, 0), row by row: OpenCV's order.
std::vector<cv::Point3f> BoardPoints(const ChessboardOptions& o) {
  std::vector<cv::Point3f> points;
  for (int j = 0; j < o.rows; ++j) {
    for (int i = 0; i < o.cols; ++i) {
      points.emplace_back(static_cast<float>(i * o.square_mm), static_cast<float>(j * o.square_mm), 0.f);
    }
  }
  return points;
}

std::vector<cv::Point2f> ToCv(const std::vector<Eigen::Vector2d>& points) {
  std::vector<cv::Point2f> out;
  for (const Eigen::Vector2d& p : points) out.emplace_back(static_cast<float>(p.x()), static_cast<float>(p.y()));
  return out;
}

double ReprojectionRms(const std::vector<cv::Point3f>& board, const std::vector<cv::Point2f>& image,
                       const cv::Mat& rvec, const cv::Mat& tvec, const cv::Mat& k, const cv::Mat& d) {
  std::vector<cv::Point2f> projected;
  cv::projectPoints(board, rvec, tvec, k, d, projected);
  double sum = 0;
  for (size_t i = 0; i < image.size(); ++i) {
    const cv::Point2f e = projected[i] - image[i];
    sum += static_cast<double>(e.x) * e.x + static_cast<double>(e.y) * e.y;
  }
  return std::sqrt(sum / image.size());
}

cv::Mat CameraMatrixCv(const Camera& camera) {
  cv::Mat k;
  cv::eigen2cv(camera.CameraMatrix(), k);
  return k;
}

cv::Mat DistortionCv(const Camera& camera) { return cv::Mat(camera.distortion, true).reshape(1, 1); }

}  // namespace

bool ChessboardOptions::Check(std::string* why) const {
  const char* problem = nullptr;
  if (cols < 3 || rows < 3) problem = "the board needs at least 3x3 inner corners (COLSxROWS counts inner corners)";
  else if (!(square_mm > 0) || !std::isfinite(square_mm)) problem = "the square size must be > 0 mm";
  else if (distortion_coefficients != 4 && distortion_coefficients != 5 && distortion_coefficients != 8)
    problem = "distortion_coefficients must be 4, 5 or 8";
  else if (subpixel_half_window_px < 1 || subpixel_half_window_px > 50)
    problem = "subpixel_half_window_px must be in [1, 50]";
  if (problem && why) *why = problem;  // `why` may be null
  return problem == nullptr;
}

bool FindChessboardCorners(const cv::Mat& image, const ChessboardOptions& options,
                           std::vector<Eigen::Vector2d>* corners) {
  JGPM_CHECK(image.depth() == CV_8U && (image.channels() == 1 || image.channels() == 3));
  cv::Mat grey = image;
  if (image.channels() == 3) cv::cvtColor(image, grey, cv::COLOR_BGR2GRAY);
  std::vector<cv::Point2f> found;
  corners->clear();
  const int flags = cv::CALIB_CB_ADAPTIVE_THRESH | cv::CALIB_CB_NORMALIZE_IMAGE |
                    (options.fast_check ? cv::CALIB_CB_FAST_CHECK : 0);
  if (!cv::findChessboardCorners(grey, cv::Size(options.cols, options.rows), found, flags)) {
    return false;
  }
  // The search window must not reach the neighbouring corners' edges.
  double min_spacing = std::numeric_limits<double>::infinity();
  for (int j = 0; j < options.rows; ++j) {
    for (int i = 0; i < options.cols; ++i) {
      const cv::Point2f& p = found[j * options.cols + i];
      if (i + 1 < options.cols) min_spacing = std::min<double>(min_spacing, cv::norm(found[j * options.cols + i + 1] - p));
      if (j + 1 < options.rows) min_spacing = std::min<double>(min_spacing, cv::norm(found[(j + 1) * options.cols + i] - p));
    }
  }
  const int half = std::max(1, std::min(options.subpixel_half_window_px, static_cast<int>(min_spacing / 2)));
  cv::cornerSubPix(grey, found, cv::Size(half, half), cv::Size(-1, -1),
                   cv::TermCriteria(cv::TermCriteria::EPS | cv::TermCriteria::COUNT, 100, 1e-4));
  for (const cv::Point2f& p : found) corners->emplace_back(p.x, p.y);
  return true;
}

int CalibrationSummary::NumUsed() const {
  return static_cast<int>(std::count_if(images.begin(), images.end(), [](const CalibrationImage& i) { return i.used; }));
}

std::string CalibrationSummary::BriefReport() const {
  char line[512];
  std::snprintf(line, sizeof(line),
                "calibrated from %d of %zu images: RMS reprojection error %.4f px, fx %.3f fy %.3f, "
                "cx %.3f cy %.3f (%dx%d), %.1f s",
                NumUsed(), images.size(), rms_px, camera.fx, camera.fy, camera.cx, camera.cy,
                camera.width, camera.height, wall_seconds);
  return line;
}

CalibrationSummary CalibrateFromImages(const std::vector<std::string>& image_paths,
                                       const ChessboardOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  const std::string where = ImagesWhere(image_paths);
  std::string why;
  if (!options.Check(&why)) ThrowInputError("chessboard options", why);

  CalibrationSummary summary;
  const int n = static_cast<int>(image_paths.size());
  summary.images.resize(n);
  std::vector<std::vector<Eigen::Vector2d>> corners(n);
  std::vector<bool> found(n, false);
  for (int i = 0; i < n; ++i) {
    CalibrationImage& image = summary.images[i];
    image.path = image_paths[i];
    const cv::Mat grey = ReadGrey(image.path);
    std::error_code error;
    if (!std::filesystem::is_regular_file(image.path, error)) {
      image.rejected_because = "no such file";
    } else if (grey.empty()) {
      image.rejected_because = "not a readable image";
    } else {
      image.width = grey.cols;
      image.height = grey.rows;
      found[i] = FindChessboardCorners(grey, options, &corners[i]);
      if (!found[i]) image.rejected_because = "no " + BoardName(options) + " chessboard found";
    }
    if (options.progress) options.progress(i + 1, n);
  }

  // The image size most boards were found at (the first such on a tie).
  std::map<std::pair<int, int>, int> count;
  std::pair<int, int> size{0, 0};
  int best = 0;
  for (int i = 0; i < n; ++i) {
    if (!found[i]) continue;
    const std::pair<int, int> s{summary.images[i].width, summary.images[i].height};
    if (++count[s] > best) {
      best = count[s];
      size = s;
    }
  }
  std::vector<std::vector<cv::Point3f>> board_points;
  std::vector<std::vector<cv::Point2f>> image_points;
  std::vector<int> used;
  for (int i = 0; i < n; ++i) {
    CalibrationImage& image = summary.images[i];
    if (!found[i]) continue;
    if (std::pair(image.width, image.height) != size) {
      image.rejected_because = "size " + SizeName(image.width, image.height) + " differs from the " +
                               SizeName(size.first, size.second) + " of most images";
      continue;
    }
    image.used = true;
    used.push_back(i);
    board_points.push_back(BoardPoints(options));
    image_points.push_back(ToCv(corners[i]));
  }
  if (used.size() < 3) {
    std::string message = std::to_string(used.size()) + " usable chessboard image" + (used.size() == 1 ? "" : "s") +
                          " of " + std::to_string(n) + ", at least 3 needed";
    std::string rejected;
    for (const CalibrationImage& image : summary.images) {
      if (image.used) continue;
      rejected += (rejected.empty() ? "; rejected: " : ", ") +
                  std::filesystem::path(image.path).filename().string() + " (" + image.rejected_because + ")";
    }
    ThrowInputError(where, message + rejected);
  }

  int flags = 0;
  if (options.distortion_coefficients == 4) flags |= cv::CALIB_FIX_K3;
  if (options.distortion_coefficients == 8) flags |= cv::CALIB_RATIONAL_MODEL;
  cv::Mat k, d;
  std::vector<cv::Mat> rvecs, tvecs;
  try {
    summary.rms_px = cv::calibrateCamera(
        board_points, image_points, cv::Size(size.first, size.second), k, d, rvecs, tvecs, flags,
        cv::TermCriteria(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 100, std::numeric_limits<double>::epsilon()));
  } catch (const cv::Exception& e) {
    ThrowInputError(where, "OpenCV's calibration failed: " + e.msg);
  }
  k.convertTo(k, CV_64F);
  d.convertTo(d, CV_64F);
  Camera& camera = summary.camera;
  camera.width = size.first;
  camera.height = size.second;
  camera.fx = k.at<double>(0, 0);
  camera.fy = k.at<double>(1, 1);
  camera.cx = k.at<double>(0, 2);
  camera.cy = k.at<double>(1, 2);
  camera.distortion.assign(d.begin<double>(), d.end<double>());
  camera.distortion.resize(options.distortion_coefficients, 0.0);
  if (!camera.Check(&why)) ThrowInputError(where, "the calibration gave an unusable camera: " + why);
  for (size_t v = 0; v < used.size(); ++v) {
    CalibrationImage& image = summary.images[used[v]];
    image.reprojection_rms_px = ReprojectionRms(board_points[v], image_points[v], rvecs[v], tvecs[v], k, d);
    cv::Mat r;
    cv::Rodrigues(rvecs[v], r);
    cv::cv2eigen(r, image.cam_from_board_rotation);
    for (int a = 0; a < 3; ++a) image.cam_from_board_translation_mm[a] = tvecs[v].at<double>(a);
  }
  summary.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return summary;
}

void CheckFloorBoard(const ChessboardOptions& options) {
  std::string why;
  if (!options.Check(&why)) ThrowInputError("chessboard options", why);
  if (options.cols % 2 == options.rows % 2) {
    ThrowInputError("chessboard " + BoardName(options),
                    "placing a camera on the floor needs a board with one odd and one even count of inner corners "
                    "(e.g. 9x6): this one looks the same after a half turn, so its first corner is ambiguous");
  }
}

FloorPlacement PlaceCameraFromFloorBoard(const Camera& intrinsics, const std::string& image_path,
                                         const ChessboardOptions& options) {
  CheckFloorBoard(options);
  std::string why;
  JGPM_CHECK(intrinsics.Check(&why));
  CheckInputFile(image_path, "a chessboard image");
  const cv::Mat grey = ReadGrey(image_path);
  if (grey.empty()) ThrowInputError(image_path, "not a readable image");
  if (grey.cols != intrinsics.width || grey.rows != intrinsics.height) {
    ThrowInputError(image_path, "the image is " + SizeName(grey.cols, grey.rows) + ", the camera's images are " +
                                    SizeName(intrinsics.width, intrinsics.height));
  }
  std::vector<Eigen::Vector2d> corners;
  if (!FindChessboardCorners(grey, options, &corners))
    ThrowInputError(image_path, "no " + BoardName(options) + " chessboard found");

  const std::vector<cv::Point3f> board = BoardPoints(options);
  const std::vector<cv::Point2f> image = ToCv(corners);
  const cv::Mat k = CameraMatrixCv(intrinsics), d = DistortionCv(intrinsics);
  cv::Mat rvec, tvec;
  cv::solvePnP(board, image, k, d, rvec, tvec, false, cv::SOLVEPNP_IPPE);
  cv::solvePnPRefineLM(board, image, k, d, rvec, tvec);

  FloorPlacement placement;
  placement.reprojection_rms_px = ReprojectionRms(board, image, rvec, tvec, k, d);
  cv::Mat r;
  cv::Rodrigues(rvec, r);
  Eigen::Matrix3d cam_from_board;
  cv::cv2eigen(r, cam_from_board);
  // world = (x_board, -z_board, y_board).
  Eigen::Matrix3d world_from_board;
  world_from_board << 1, 0, 0,
                      0, 0, -1,
                      0, 1, 0;
  placement.camera = intrinsics;
  placement.camera.cam_from_world_rotation = cam_from_board * world_from_board.transpose();
  for (int a = 0; a < 3; ++a) placement.camera.cam_from_world_translation_mm[a] = tvec.at<double>(a);
  return placement;
}

}  // namespace jgpm
