#include "calibration/synthetic_chessboard.h"

#include <algorithm>
#include <cmath>
#include <random>

#include <opencv2/imgproc.hpp>

#include "io/base/error.h"

namespace jgpm {

bool SyntheticChessboardOptions::Check(std::string* why) const {
  const char* problem = nullptr;
  auto grey = [](double g) { return std::isfinite(g) && g >= 0 && g <= 255; };
  if (cols < 3 || rows < 3) problem = "the board needs at least 3x3 inner corners";
  else if (!(square_mm > 0) || !std::isfinite(square_mm)) problem = "square_mm must be > 0";
  else if (!grey(black) || !grey(white) || !grey(background)) problem = "grey levels must be in [0, 255]";
  else if (!(blur_sigma_px >= 0) || blur_sigma_px > 20) problem = "blur_sigma_px must be in [0, 20]";
  else if (!(noise_stddev >= 0) || !std::isfinite(noise_stddev)) problem = "noise_stddev must be >= 0";
  if (problem && why) *why = problem;  // `why` may be null
  return problem == nullptr;
}

Eigen::Vector3d BoardPose::CornerInWorld(double i, double j, double square_mm) const {
  return first_corner_in_world_mm + world_from_board_rotation * Eigen::Vector3d(i * square_mm, j * square_mm, 0);
}

bool ChessboardCornerPixels(const Camera& camera, const SyntheticChessboardOptions& board,
                            const BoardPose& pose, std::vector<Eigen::Vector2d>* pixels) {
  pixels->assign(static_cast<size_t>(board.cols) * board.rows, Eigen::Vector2d::Zero());
  for (int j = 0; j < board.rows; ++j) {
    for (int i = 0; i < board.cols; ++i) {
      if (!camera.Project(pose.CornerInWorld(i, j, board.square_mm), &(*pixels)[j * board.cols + i])) return false;
    }
  }
  return true;
}

ChessboardRenderer::ChessboardRenderer(const Camera& intrinsics, int supersampling)
    : intrinsics_(intrinsics), supersampling_(supersampling) {
  std::string why;
  JGPM_CHECK(intrinsics.Check(&why));
  JGPM_CHECK(supersampling >= 1 && supersampling <= 16);
  // Rays in the camera frame: the camera at the world origin.
  Camera at_origin = intrinsics;
  at_origin.cam_from_world_rotation.setIdentity();
  at_origin.cam_from_world_translation_mm.setZero();
  const int n = supersampling;
  const Camera& camera = intrinsics;
  // Sample offsets from the pixel centre (pixel centres are at integer coordinates), in
  // the canonical multi-jittered arrangement (a plain n x n grid would quantise the
  // position of an edge along the pixel grid to 1/n px).
  std::vector<Eigen::Vector2d> offsets;
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) offsets.emplace_back((i + (j + 0.5) / n) / n - 0.5, (j + (i + 0.5) / n) / n - 0.5);
  }
  const int samples_per_row = camera.width * n * n;
  ray_xy_.resize(2 * static_cast<size_t>(samples_per_row) * camera.height);
  Eigen::Matrix2Xd pixels(2, samples_per_row);
  for (int y = 0; y < camera.height; ++y) {
    for (int x = 0; x < camera.width; ++x) {
      for (int k = 0; k < n * n; ++k) pixels.col(x * n * n + k) = Eigen::Vector2d(x, y) + offsets[k];
    }
    const Eigen::Matrix3Xd rays = at_origin.PixelRaysInWorld(pixels);
    float* out = &ray_xy_[2 * static_cast<size_t>(y) * samples_per_row];
    for (int k = 0; k < samples_per_row; ++k) {
      out[2 * k] = static_cast<float>(rays(0, k) / rays(2, k));
      out[2 * k + 1] = static_cast<float>(rays(1, k) / rays(2, k));
    }
  }
}

cv::Mat ChessboardRenderer::Render(const Camera& camera, const SyntheticChessboardOptions& board,
                                   const BoardPose& pose) const {
  std::string why;
  JGPM_CHECK(board.Check(&why));
  JGPM_CHECK(camera.width == intrinsics_.width && camera.height == intrinsics_.height &&
             camera.CameraMatrix() == intrinsics_.CameraMatrix() && camera.distortion == intrinsics_.distortion);
  const SyntheticChessboardOptions& o = board;
  const int n = supersampling_;
  // The board's origin and axes in the camera frame.
  const Eigen::Matrix3d axes = camera.cam_from_world_rotation * pose.world_from_board_rotation;
  const Eigen::Vector3d origin = camera.ToCamera(pose.first_corner_in_world_mm);
  const Eigen::Vector3d ex = axes.col(0), ey = axes.col(1), ez = axes.col(2);
  const double ez_origin = ez.dot(origin), ex_origin = ex.dot(origin), ey_origin = ey.dot(origin);
  const double s = o.square_mm;
  // Board extent in board coordinates: squares, then the margin one square wide.
  const double squares_x0 = -s, squares_x1 = o.cols * s, squares_y0 = -s, squares_y1 = o.rows * s;
  const double margin_x0 = -2 * s, margin_x1 = (o.cols + 1) * s;
  const double margin_y0 = -2 * s, margin_y1 = (o.rows + 1) * s;

  cv::Mat_<double> sum(camera.height, camera.width, 0.0);
  const int samples_per_pixel = n * n;
  for (int y = 0; y < camera.height; ++y) {
    const float* xy = &ray_xy_[2 * static_cast<size_t>(y) * camera.width * samples_per_pixel];
    for (int k = 0; k < camera.width * samples_per_pixel; ++k) {
      const Eigen::Vector3d d(xy[2 * k], xy[2 * k + 1], 1.0);
      double grey = o.background;
      const double denominator = ez.dot(d);
      // The ray meets the plane at camera-frame point t d, t > 0 (in front of the camera).
      if (denominator != 0) {
        const double t = ez_origin / denominator;
        if (t > 0) {
          const double bx = t * ex.dot(d) - ex_origin, by = t * ey.dot(d) - ey_origin;
          if (bx >= squares_x0 && bx < squares_x1 && by >= squares_y0 && by < squares_y1) {
            const long a = static_cast<long>(std::floor(bx / s)), b = static_cast<long>(std::floor(by / s));
            grey = (a + b) % 2 == 0 ? o.black : o.white;
          } else if (bx >= margin_x0 && bx < margin_x1 && by >= margin_y0 && by < margin_y1) {
            grey = o.white;
          }
        }
      }
      sum(y, k / samples_per_pixel) += grey;
    }
  }
  sum /= samples_per_pixel;
  if (o.blur_sigma_px > 0) cv::GaussianBlur(sum, sum, cv::Size(0, 0), o.blur_sigma_px, o.blur_sigma_px, cv::BORDER_REPLICATE);
  std::mt19937 random(o.noise_seed);
  std::normal_distribution<double> noise(0.0, o.noise_stddev);
  cv::Mat image(camera.height, camera.width, CV_8UC1);
  for (int y = 0; y < camera.height; ++y) {
    for (int x = 0; x < camera.width; ++x) {
      double grey = sum(y, x);
      if (o.noise_stddev > 0) grey += noise(random);
      image.at<uint8_t>(y, x) = static_cast<uint8_t>(std::clamp(std::lround(grey), 0L, 255L));
    }
  }
  return image;
}

}  // namespace jgpm
