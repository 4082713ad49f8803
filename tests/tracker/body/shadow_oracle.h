// Test oracle for shadows on the floor: ray-cast, a floor pixel is in the shadow when the
// way from its floor point to the light enters a part (IntersectCapsule, itself checked
// against brute force in ray_caster_test).
#pragma once

#include <limits>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core/mat.hpp>

#include "calibration/camera.h"
#include "tracker/body/ray_caster.h"

namespace jgpm::test {

// Per pixel, row by row, where its ray meets the floor y = floor_mm (NaN where it does not).
inline Eigen::Matrix3Xd FloorPoints(const Camera& camera, double floor_mm) {
  Eigen::Matrix2Xd pixels(2, camera.width * camera.height);
  for (int v = 0; v < camera.height; ++v)
    for (int u = 0; u < camera.width; ++u) pixels.col(v * camera.width + u) << u, v;
  Eigen::Matrix3Xd points = camera.PixelRaysInWorld(pixels);
  const Eigen::Vector3d eye = camera.CentreInWorld();
  for (int i = 0; i < points.cols(); ++i) {
    const Eigen::Vector3d ray = points.col(i);
    points.col(i) = ray.y() < -1e-9 ? Eigen::Vector3d(eye + ray * ((floor_mm - eye.y()) / ray.y()))
                                    : Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
  }
  return points;
}

// Sets to 255 the pixels of `mask` (CV_8UC1 of the camera's size) whose floor point is in
// the shadow of `parts` under a light from `light` (unit, towards it); only floor points
// within `reach_mm` of `near` on the floor are tried (the rest of the floor costs time).
inline void AddRayCastShadow(const Camera& camera, const std::vector<Capsule>& parts, const Eigen::Vector3d& light,
                             double floor_mm, cv::Mat* mask, const Eigen::Vector3d& near = Eigen::Vector3d::Zero(),
                             double reach_mm = std::numeric_limits<double>::infinity()) {
  const Eigen::Matrix3Xd floor = FloorPoints(camera, floor_mm);
  for (int i = 0; i < floor.cols(); ++i) {
    const Eigen::Vector3d p = floor.col(i);
    if (!p.allFinite() || Eigen::Vector2d(p.x() - near.x(), p.z() - near.z()).norm() > reach_mm) continue;
    double t;
    for (const Capsule& c : parts)
      if (IntersectCapsule(p, light, c, &t, nullptr)) {
        mask->at<uchar>(i / camera.width, i % camera.width) = 255;
        break;
      }
  }
}

}  // namespace jgpm::test
