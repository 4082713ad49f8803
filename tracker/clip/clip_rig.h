// The default camera rig of a synthetic clip: 1-4 cameras on a ring about the walk.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "calibration/camera.h"

namespace jgpm {

struct RigOptions {
  int num_cameras = 2;             // 1-4: side view, front view, then around the ring
  int width = 320;                 // image size, pixels
  int height = 240;
  double ring_radius_mm = 4500;    // from the walk's centre (grown when the walk is longer)
  double camera_height_mm = 1500;  // above the floor

  bool Check(std::string* why) const;
};

// Cameras on a ring about the centre of the walk (the root's path), looking at its middle
// at 1 m height: first the side view (perpendicular to the walking direction), then the
// front view, then the others around the ring (3: 120 degrees apart; 4: every 90). Each
// camera's focal length is the largest that keeps every joint, padded by a body's width,
// inside its image in every frame.
std::vector<Camera> DefaultRig(const std::vector<Eigen::Matrix3Xd>& joint_in_world_mm, const RigOptions& options);

}  // namespace jgpm
