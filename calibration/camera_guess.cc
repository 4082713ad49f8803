#include "calibration/camera_guess.h"

#include <cmath>
#include <numbers>

namespace jgpm {

Camera GuessCamera(const std::string& name, int width, int height, const CameraGuess& guess) {
  const double focal = (width / 2.0) / std::tan(guess.fov_deg * std::numbers::pi / 360);
  const double tilt = guess.tilt_deg * std::numbers::pi / 180;
  const Eigen::Vector3d centre(0, guess.height_mm, 0);
  const Eigen::Vector3d target = centre + Eigen::Vector3d(0, -std::sin(tilt), std::cos(tilt)) * 1000;
  return LookAtCamera(name, width, height, focal, centre, target);
}

}  // namespace jgpm
