// The camera that calibration from walkers fits (walker_calibration.h) and that placing
// several cameras refines (rig_placement.h): four parameters, log focal (px), tilt down
// (rad), roll (rad) and log height (mm), for a camera above its own world's origin looking
// along +z. Logs keep the focal length and height positive and make their steps relative.
//
// cam_from_world is R = Rz(roll) R0(tilt), R0's rows the camera's right, down and forward
// axes in the world (right = -x, forward (0, -sin tilt, cos tilt)): LookAtCamera's camera,
// rolled about its axis.
#pragma once

#include <array>
#include <cmath>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "calibration/camera.h"

namespace jgpm {

enum { kLogFocal, kTilt, kRoll, kLogHeight, kWalkerCameraParameters };
using WalkerCameraParameters = std::array<double, kWalkerCameraParameters>;

// The world direction R^T (q / f, 1) of the ray through the "ideal" pixel q: its offset from
// the principal point, undistorted (IdealPixel). R0 is symmetric.
template <typename T>
void WalkerCameraRay(const T* camera, const Eigen::Vector2d& q, T* w) {
  using std::cos, std::exp, std::sin;
  const T f = exp(camera[kLogFocal]);
  const T ct = cos(camera[kTilt]), st = sin(camera[kTilt]);
  const T cr = cos(camera[kRoll]), sr = sin(camera[kRoll]);
  const T dx = T(q.x()) / f, dy = T(q.y()) / f;
  const T ex = cr * dx + sr * dy, ey = -sr * dx + cr * dy, ez = T(1);
  w[0] = -ex;
  w[1] = -ct * ey - st * ez;
  w[2] = -st * ey + ct * ez;
}

// `pixel` of a camera with `intrinsics` (their pose ignored) as an ideal pixel, in units of
// the intrinsics' fx: undistorted through the lens when it has one.
inline Eigen::Vector2d IdealPixel(const Camera& intrinsics, const Eigen::Vector2d& pixel) {
  Camera lens = intrinsics;
  lens.cam_from_world_rotation.setIdentity();
  lens.cam_from_world_translation_mm.setZero();
  const Eigen::Vector3d ray = lens.PixelRaysInWorld(pixel).col(0);
  return ray.head<2>() / ray.z() * intrinsics.fx;
}

// The camera of `parameters` with `intrinsics`' image size, principal point and lens (its
// focal length replaced by the parameters' unless `keep_focal`), named "cam0".
inline Camera WalkerCamera(const Camera& intrinsics, const WalkerCameraParameters& parameters, bool keep_focal) {
  const double tilt = parameters[kTilt];
  const Eigen::Vector3d centre(0, std::exp(parameters[kLogHeight]), 0);
  const Camera looking = LookAtCamera("cam0", intrinsics.width, intrinsics.height, std::exp(parameters[kLogFocal]),
                                      centre, centre + Eigen::Vector3d(0, -std::sin(tilt), std::cos(tilt)) * 1000);
  Camera placed = keep_focal ? intrinsics : looking;
  if (!keep_focal) placed.cx = intrinsics.cx, placed.cy = intrinsics.cy, placed.distortion = intrinsics.distortion;
  placed.name = "cam0";
  placed.cam_from_world_rotation =
      Eigen::AngleAxisd(parameters[kRoll], Eigen::Vector3d::UnitZ()).toRotationMatrix() * looking.cam_from_world_rotation;
  placed.cam_from_world_translation_mm = -placed.cam_from_world_rotation * centre;
  return placed;
}

}  // namespace jgpm
