// The camera the calibration tests render their chessboards through: 640x480, barrel
// distortion, tangential terms, the principal point a few pixels off-centre, at the world
// origin. Calibration must recover it.
#pragma once

#include "calibration/camera.h"

namespace jgpm::test {

inline Camera TrueCamera() {
  Camera c;
  c.name = "truth";
  c.width = 640;
  c.height = 480;
  c.fx = 521.3;
  c.fy = 519.6;
  c.cx = 325.4;
  c.cy = 236.8;
  c.distortion = {-0.2, 0.05, 0.0008, -0.0006, 0.0};
  return c;
}

}  // namespace jgpm::test
