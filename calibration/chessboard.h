// Camera calibration from chessboard images (OpenCV: cv::findChessboardCorners with
// adaptive threshold and normalisation, cv::cornerSubPix, cv::calibrateCamera), and
// placing a calibrated camera in the world from one image of a chessboard lying on the
// floor (cv::solvePnP).
//
// Board convention: `cols` x `rows` counts INNER corners, as cv::findChessboardCorners'
// patternSize (a board of 10 x 7 squares has 9 x 6 inner corners); squares of side
// `square_mm`. Corner k of OpenCV's order (row by row) is at board point
// ((k % cols) * square_mm, (k / cols) * square_mm, 0). calibration/synthetic_chessboard.h
// renders boards with exactly this convention.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "calibration/camera.h"

namespace jgpm {

struct ChessboardOptions {
  int cols = 9;                  // inner corners along a board row (patternSize.width), >= 3
  int rows = 6;                  // inner corners along a board column (patternSize.height), >= 3
  double square_mm = 25;         // side of one square as printed: measure it
  // Distortion model fitted: 4 (k1 k2 p1 p2; k3 held at 0), 5 (k1 k2 p1 p2 k3, OpenCV's
  // default) or 8 (rational model, k4 k5 k6 too: wide-angle lenses).
  int distortion_coefficients = 5;
  // Half-size of cv::cornerSubPix's search window, pixels (5: an 11x11 window). Shrunk
  // per image to half the smallest spacing of the detected corners, so small boards work.
  int subpixel_half_window_px = 5;
  // Adds CALIB_CB_FAST_CHECK: an image without a board is given up in milliseconds instead
  // of seconds (a noisy one can take 5 s), at the risk of missing a board in a poor image.
  bool fast_check = false;
  // Called after each image is examined with (images done, images in all); may be empty.
  std::function<void(int done, int total)> progress;

  bool Check(std::string* why) const;
};

// Finds the board's inner corners in an 8-bit image (grey or BGR) and refines them to
// sub-pixel accuracy; `corners` in OpenCV's order (see above). False if not found.
bool FindChessboardCorners(const cv::Mat& image, const ChessboardOptions& options,
                           std::vector<Eigen::Vector2d>* corners);

// What became of one calibration image.
struct CalibrationImage {
  std::string path;
  bool used = false;
  std::string rejected_because;       // when !used, e.g. "no 9x6 chessboard found"
  int width = 0, height = 0;          // 0 when unreadable
  double reprojection_rms_px = -1;    // when used: RMS over its corners of the fitted camera
  // When used: the board's pose, x_cam = R x_board + t, millimetres.
  Eigen::Matrix3d cam_from_board_rotation = Eigen::Matrix3d::Identity();
  Eigen::Vector3d cam_from_board_translation_mm = Eigen::Vector3d::Zero();
};

struct CalibrationSummary {
  Camera camera;                       // intrinsics and image size; at the world origin
  std::vector<CalibrationImage> images;  // in the order given
  double rms_px = 0;                   // RMS reprojection error over every corner used
  double wall_seconds = 0;

  int NumUsed() const;
  // One line: images used, RMS, focal lengths, principal point, wall time.
  std::string BriefReport() const;
};

// Calibrates from the images at `image_paths`. An image is rejected (with the reason in
// the summary) when it is missing or not a readable image, has no board, or its size
// differs from the size most boards were found at (on a tie, the size that got there
// first). InputError (naming the images' folder) when the options are bad or fewer than 3
// images are usable, listing the rejected ones and why, or when OpenCV's calibration
// fails.
CalibrationSummary CalibrateFromImages(const std::vector<std::string>& image_paths,
                                       const ChessboardOptions& options);

// Placing a camera with a board lying flat on the floor (world y = 0, y up, millimetres).
// The world origin is the board's first inner corner (corner 0 in OpenCV's order); world
// +x runs along the board's rows (from corner 0 to corner cols - 1) and +z along its
// columns (from corner 0 to corner (rows - 1) * cols): right-handed with y up, so seen
// from above +z is +x turned 90 degrees clockwise. In board coordinates that is
// world = (x_board, -z_board, y_board): the board's z axis points down into the floor.
//
// For corner 0 to be a fixed corner of the physical board, one count must be odd and the
// other even: the two black corner squares are then on one side of the board and corner
// 0 is at one of them. With a 9x6 board (10 x 7 squares) they are on a short side: stand
// there looking along the board (+x); the origin is the black corner on your left and +z
// runs to your right. Boards with both counts odd or both even look the same after a
// half turn, so they are refused (InputError).
struct FloorPlacement {
  Camera camera;                    // the intrinsics given, with cam_from_world set
  double reprojection_rms_px = 0;   // RMS over the board's corners
};

// OpenCV's detector needs the board seen from well above and with big squares. Measured
// with a 640x480 camera (f = 520 px) 1.5 m up, from 8 directions round the board: 2 m
// away horizontally (37 degrees elevation) a 7x4 board of 150 mm squares was found from
// all 8, a 9x6 board of 100 mm squares from 3; 2.5 m away (31 degrees) each from 3 or
// fewer; 1.5 m away (45 degrees) both from 7 or 8. Lay the board near the camera.
//
// `intrinsics` must pass Camera::Check; its extrinsics are ignored. InputError naming the
// image when it is missing or cannot be read, its size differs from the camera's, or the
// board is not found; and CheckFloorBoard's.
FloorPlacement PlaceCameraFromFloorBoard(const Camera& intrinsics, const std::string& image_path,
                                         const ChessboardOptions& options);

// InputError unless the options are good and the board has a first corner to go by (one
// count odd, the other even), naming the board.
void CheckFloorBoard(const ChessboardOptions& options);

}  // namespace jgpm
