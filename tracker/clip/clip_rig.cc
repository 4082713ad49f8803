#include "tracker/clip/clip_rig.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "io/base/error.h"

namespace jgpm {

bool RigOptions::Check(std::string* why) const {
  auto fail = [&](const std::string& what) { if (why) *why = what; return false; };
  if (num_cameras < 1 || num_cameras > 4) return fail("cameras: expected 1 to 4");
  if (width < 32 || height < 32 || width > 4096 || height > 4096)
    return fail("image size: expected 32 to 4096 pixels a side");
  if (!(ring_radius_mm >= 1000 && ring_radius_mm <= 50000)) return fail("ring radius: expected 1000 to 50000 mm");
  if (!(camera_height_mm > 0 && camera_height_mm < 10000)) return fail("camera height: expected 0 to 10000 mm");
  return true;
}

std::vector<Camera> DefaultRig(const std::vector<Eigen::Matrix3Xd>& joints, const RigOptions& options) {
  JGPM_CHECK(!joints.empty() && options.Check(nullptr));
  // The walk's centre and direction on the floor, from the root's path.
  Eigen::Vector2d lo(1e300, 1e300), hi(-1e300, -1e300);
  for (const Eigen::Matrix3Xd& j : joints) {
    const Eigen::Vector2d root(j(0, 0), j(2, 0));
    lo = lo.cwiseMin(root);
    hi = hi.cwiseMax(root);
  }
  const Eigen::Vector2d centre = 0.5 * (lo + hi);
  Eigen::Vector2d walk(joints.back()(0, 0) - joints.front()(0, 0), joints.back()(2, 0) - joints.front()(2, 0));
  walk = walk.norm() > 300 ? walk.normalized() : Eigen::Vector2d(0, 1);
  const Eigen::Vector2d side(walk.y(), -walk.x());
  // A camera in line with the walk must stay ~2 m clear of the walker's nearest point.
  double reach = 0;
  for (const Eigen::Matrix3Xd& j : joints)
    for (int c = 0; c < j.cols(); ++c) reach = std::max(reach, (Eigen::Vector2d(j(0, c), j(2, c)) - centre).norm());
  const double radius = std::max(options.ring_radius_mm, reach + 2000);
  static const std::vector<std::vector<double>> kAzimuthsDeg = {
      {90}, {90, 0}, {90, 210, 330}, {90, 0, 270, 180}};
  std::vector<Camera> cameras;
  for (double azimuth : kAzimuthsDeg[options.num_cameras - 1]) {
    const double a = azimuth * std::numbers::pi / 180;
    const Eigen::Vector2d at = centre + radius * (std::cos(a) * walk + std::sin(a) * side);
    Camera camera = LookAtCamera("cam" + std::to_string(cameras.size()), options.width, options.height,
                                 1.0, {at.x(), options.camera_height_mm, at.y()},
                                 {centre.x(), 1000, centre.y()});
    // Largest focal length with every joint, padded by 250 mm (half a body's width) and a
    // 3 px border, in view.
    constexpr double kPadMm = 250, kBorderPx = 3;
    double tan_x = 1e-6, tan_y = 1e-6;
    for (const Eigen::Matrix3Xd& j : joints)
      for (int c = 0; c < j.cols(); ++c) {
        const Eigen::Vector3d p = camera.ToCamera(j.col(c));
        const double z = std::max(p.z() - kPadMm, 100.0);
        tan_x = std::max(tan_x, (std::abs(p.x()) + kPadMm) / z);
        tan_y = std::max(tan_y, (std::abs(p.y()) + kPadMm) / z);
      }
    const double f = std::min((options.width / 2.0 - kBorderPx) / tan_x, (options.height / 2.0 - kBorderPx) / tan_y);
    camera.fx = camera.fy = f;
    cameras.push_back(camera);
  }
  return cameras;
}

}  // namespace jgpm
