// A camera for a video nobody calibrated (`jgpm track --camera-guess`): the image size, a
// horizontal field of view, placed at a height above the floor at the world origin,
// looking along +z tilted down. Good enough to see a walk; the 3-D figures are only as
// right as the guess.
#pragma once

#include <string>

#include "calibration/camera.h"

namespace jgpm {

struct CameraGuess {
  double fov_deg = 60;      // a typical webcam's horizontal field of view
  double height_mm = 1200;  // a camera on a tripod or desk
  double tilt_deg = 10;     // looking slightly down, so that the feet are in view
};

Camera GuessCamera(const std::string& name, int width, int height, const CameraGuess& guess);

}  // namespace jgpm
