// The cameras of a synthetic clip when none are given, fitted to the walk: the lab's ring
// (1-4 cameras at 1.5 m about the walk, each zoomed to keep the walker in view), fixed
// surveillance cameras high above it, or one webcam near it. And how a real calibration
// of them would be wrong.
#pragma once

#include <cstdint>
#include <random>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "calibration/camera.h"

namespace jgpm {

enum class RigKind {
  kRing,          // the lab: cameras on a ring at 1.5 m, side view first (DefaultRig)
  kSurveillance,  // 1-4 fixed cameras 4-8 m up, 8-19 m away, looking down 20-40 degrees;
                  // people 60-150 px tall
  kWebcam,        // one camera 1-1.5 m up with a 60-90 degree field of view, beside the
                  // walk and near it (1-2.5 m): the walker leaves the view at the sides,
                  // and the feet are cut off near the middle
};
std::string_view RigKindName(RigKind kind);  // "ring", "surveillance", "webcam"
bool ParseRigKind(std::string_view name, RigKind* kind);

struct RigOptions {
  RigKind kind = RigKind::kRing;
  int num_cameras = 2;             // 1-4: side view, front view, then around the ring
                                   // (the webcam rig has one)
  int width = 0;                   // image size, pixels; 0: the rig's own (ring 320 x 240,
  int height = 0;                  // surveillance and webcam 640 x 480)
  double ring_radius_mm = 4500;    // ring: from the walk's centre (grown when the walk is longer)
  double camera_height_mm = 1500;  // ring: above the floor

  bool Check(std::string* why) const;
  int Width() const;   // the size used
  int Height() const;
};

// Cameras on a ring about the centre of the walk (the root's path), looking at its middle
// at 1 m height: first the side view (perpendicular to the walking direction), then the
// front view, then the others around the ring (3: 120 degrees apart; 4: every 90). Each
// camera's focal length is the largest that keeps every joint, padded by a body's width,
// inside its image in every frame.
std::vector<Camera> DefaultRig(const std::vector<Eigen::Matrix3Xd>& joint_in_world_mm, const RigOptions& options);

// The rig options.kind asks for, fitted to the walk; the surveillance and webcam rigs are
// drawn from `seed` (heights, distances, angles, fields of view within the ranges above).
std::vector<Camera> MakeRig(const std::vector<Eigen::Matrix3Xd>& joint_in_world_mm, const RigOptions& options,
                            uint64_t seed);

// The camera a real calibration would have given (`scale` 1: focal length off by up to
// 1.5%, principal point by up to 4 px, orientation by up to 0.7 degrees about a random
// axis, centre by up to 30 mm in a random direction; every amount times `scale`, drawn
// uniformly from `rng`). Scale 0 returns the camera as it is.
Camera Miscalibrate(const Camera& camera, double scale, std::mt19937_64* rng);

}  // namespace jgpm
