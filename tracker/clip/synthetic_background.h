// The static scene behind the synthetic walker: a tiled floor (y = 0) inside a round room
// with panelled walls, drawn by casting each pixel's rays (2 x 2 per pixel, averaged) so
// every camera of a rig sees the same, consistently placed texture. Background
// subtraction in the tracker has to learn it, as it would a real room.
#pragma once

#include <Eigen/Core>
#include <opencv2/core/mat.hpp>

#include "calibration/camera.h"

namespace jgpm {

// BGR image of the camera's size. `room_centre_mm`: the walls are a cylinder of radius
// `room_radius_mm` about this point's vertical axis, `wall_height_mm` high under a plain
// ceiling (a camera must be inside: raise both for cameras high and far away).
cv::Mat RenderBackground(const Camera& camera, const Eigen::Vector3d& room_centre_mm,
                         double room_radius_mm = 12000, double wall_height_mm = 3000);

}  // namespace jgpm
