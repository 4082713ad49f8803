// Synthetic chessboard images: a grey chessboard rendered through a known Camera (with its
// lens distortion) at a known pose. The oracle of the calibration tests and a demo source
// of calibration images; deliberately simple: every sample ray is intersected with the
// board plane and coloured (no lighting), then the image is blurred and noise added.
//
// Board convention (the one cv::findChessboardCorners reports): the board has `cols` x
// `rows` INNER corners (its patternSize) and (cols + 1) x (rows + 1) squares of side
// `square_mm`. In board coordinates (millimetres, z = 0 on the board) inner corner (i, j),
// i < cols along a row, j < rows down a column, is at (i * square_mm, j * square_mm, 0).
// Square (a, b), a in [-1, cols - 1], b in [-1, rows - 1], covers [a s, (a + 1) s] x
// [b s, (b + 1) s] and is black when a + b is even: the square diagonally before corner
// (0, 0) is black. With one count odd and the other even (e.g. 9x6) this makes corner
// (0, 0) the first corner OpenCV reports when the board is seen from its -z side (the
// side the camera must be on for the board's x, y to read right, down in the image). The
// board is surrounded by a white margin one square wide, and that by the background.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "calibration/camera.h"

namespace jgpm {

// The board and how it is imaged.
struct SyntheticChessboardOptions {
  int cols = 9;                // inner corners along a board row (patternSize.width), >= 3
  int rows = 6;                // inner corners along a board column (patternSize.height), >= 3
  double square_mm = 30;       // side of one square
  double black = 30;           // grey level of the black squares
  double white = 225;          // grey level of the white squares and the margin
  double background = 180;     // grey level where the rays miss the board (light grey)
  // Gaussian blur of lens and sensor, pixels (0: none). Some blur is realistic and matters:
  // on perfectly sharp edges cv::cornerSubPix is biased by up to 0.07 px towards pixel
  // edges (measured on an exactly area-sampled corner); 1 px of blur roughly halves that.
  double blur_sigma_px = 1.0;
  double noise_stddev = 0;     // Gaussian noise added to every pixel after the blur, grey levels
  uint32_t noise_seed = 1;     // seed of that noise (the same seed gives the same image)

  bool Check(std::string* why) const;
};

// Where the board is: a board point p (board coordinates above) is in the world at
// first_corner_in_world_mm + world_from_board_rotation * p.
struct BoardPose {
  Eigen::Matrix3d world_from_board_rotation = Eigen::Matrix3d::Identity();
  Eigen::Vector3d first_corner_in_world_mm = Eigen::Vector3d::Zero();

  // World position of inner corner (i, j) (or of any board point in squares).
  Eigen::Vector3d CornerInWorld(double i, double j, double square_mm) const;
};

// The true pixel of every inner corner of `board` at `pose` seen by `camera`, row by row
// (index j * cols + i): what a perfect detector would report. False if a corner is not in
// front of the camera.
bool ChessboardCornerPixels(const Camera& camera, const SyntheticChessboardOptions& board,
                            const BoardPose& pose, std::vector<Eigen::Vector2d>* pixels);

// Renders many views through one camera's intrinsics: the undistorted ray of every sample
// is worked out once, here (about 2 s and 8 bytes per ray: 40 MB for 640x480 at 4x4).
class ChessboardRenderer {
 public:
  // `intrinsics` (image size, camera matrix, distortion; its pose is not used) must pass
  // Camera::Check. Each pixel averages n x n rays in the canonical multi-jittered
  // arrangement (n = supersampling in [1, 16]): one ray in each cell of the n x n grid
  // and in each of the n^2 columns and rows, so an edge of any direction, even one along
  // the pixel grid, moves a pixel's grey level in n^2 steps, not n.
  explicit ChessboardRenderer(const Camera& intrinsics, int supersampling = 4);

  // A CV_8UC1 image of `board` at `pose` seen by `camera`, which must have the intrinsics
  // given to the constructor (JGPM_CHECK); its pose places it. The options must pass
  // their Check (JGPM_CHECK).
  cv::Mat Render(const Camera& camera, const SyntheticChessboardOptions& board, const BoardPose& pose) const;

  const Camera& intrinsics() const { return intrinsics_; }

 private:
  Camera intrinsics_;
  int supersampling_;
  // Normalised camera coordinates (x/z, y/z) of each sample's ray: pixel by pixel, row by
  // row, n * n samples each.
  std::vector<float> ray_xy_;
};

}  // namespace jgpm
