#include "tracker/clip/clip_rig.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <Eigen/Geometry>

#include "io/base/enum_name.h"
#include "io/base/error.h"

namespace jgpm {
namespace {

constexpr double kDeg = std::numbers::pi / 180;

// The largest focal length (pixels) with every joint, padded by 250 mm (half a body's
// width) and a 3 px border, in the view of `camera` (its focal length is ignored).
double LargestFocalInView(const Camera& camera, const std::vector<Eigen::Matrix3Xd>& joints) {
  constexpr double kPadMm = 250, kBorderPx = 3;
  double tan_x = 1e-6, tan_y = 1e-6;
  for (const Eigen::Matrix3Xd& j : joints)
    for (int c = 0; c < j.cols(); ++c) {
      const Eigen::Vector3d p = camera.ToCamera(j.col(c));
      const double z = std::max(p.z() - kPadMm, 100.0);
      tan_x = std::max(tan_x, (std::abs(p.x()) + kPadMm) / z);
      tan_y = std::max(tan_y, (std::abs(p.y()) + kPadMm) / z);
    }
  return std::min((camera.width / 2.0 - kBorderPx) / tan_x, (camera.height / 2.0 - kBorderPx) / tan_y);
}

// The walk's centre and unit direction on the floor (x, z), from the root's path.
void Walk(const std::vector<Eigen::Matrix3Xd>& joints, Eigen::Vector2d* centre, Eigen::Vector2d* direction) {
  Eigen::Vector2d lo(1e300, 1e300), hi(-1e300, -1e300);
  for (const Eigen::Matrix3Xd& j : joints) {
    const Eigen::Vector2d root(j(0, 0), j(2, 0));
    lo = lo.cwiseMin(root);
    hi = hi.cwiseMax(root);
  }
  *centre = 0.5 * (lo + hi);
  Eigen::Vector2d walk(joints.back()(0, 0) - joints.front()(0, 0), joints.back()(2, 0) - joints.front()(2, 0));
  *direction = walk.norm() > 300 ? walk.normalized() : Eigen::Vector2d(0, 1);
}

std::vector<Camera> SurveillanceRig(const std::vector<Eigen::Matrix3Xd>& joints, const RigOptions& options,
                                    std::mt19937_64* rng) {
  std::uniform_real_distribution<double> u(0, 1);
  Eigen::Vector2d centre, walk;
  Walk(joints, &centre, &walk);
  const double base = 2 * std::numbers::pi * u(*rng);
  std::vector<Camera> cameras;
  for (int i = 0; i < options.num_cameras; ++i) {
    const double azimuth = base + 2 * std::numbers::pi * i / options.num_cameras + (50 * u(*rng) - 25) * kDeg;
    const double height = 4000 + 4000 * u(*rng);
    double down = (20 + 20 * u(*rng)) * kDeg;
    // Looking at the walk's centre 1 m up: at least 8 m away (then it looks down less).
    double distance = (height - 1000) / std::tan(down);
    if (distance < 8000) distance = 8000, down = std::atan((height - 1000) / distance);
    const Eigen::Vector2d at = centre + distance * Eigen::Vector2d(std::cos(azimuth), std::sin(azimuth));
    Camera camera = LookAtCamera("cam" + std::to_string(i), options.Width(), options.Height(), 1.0,
                                 {at.x(), height, at.y()}, {centre.x(), 1000, centre.y()});
    // A 1.7 m person 60-150 px tall at the walk's centre, unless that loses the walk.
    const double person_px = 60 + 90 * u(*rng);
    const double range = std::hypot(distance, height - 1000);
    camera.fx = camera.fy = std::min(person_px * range / 1700, LargestFocalInView(camera, joints));
    cameras.push_back(camera);
  }
  return cameras;
}

std::vector<Camera> WebcamRig(const std::vector<Eigen::Matrix3Xd>& joints, const RigOptions& options,
                              std::mt19937_64* rng) {
  std::uniform_real_distribution<double> u(0, 1);
  Eigen::Vector2d centre, walk;
  Walk(joints, &centre, &walk);
  const Eigen::Vector2d side(walk.y(), -walk.x());
  const double fov = (60 + 30 * u(*rng)) * kDeg, height = 1000 + 500 * u(*rng);
  // Near enough that the view spans at most 80% of the walk (the walker leaves it at the
  // ends) and that the floor under the walk is below the view (the feet are cut off
  // there: 70% of the distance at which the image's bottom edge meets the floor).
  double half_length = 0;
  for (const Eigen::Matrix3Xd& j : joints)
    half_length = std::max(half_length, (Eigen::Vector2d(j(0, 0), j(2, 0)) - centre).norm());
  const double half_vfov = std::atan(std::tan(fov / 2) * options.Height() / options.Width());
  const double distance = std::max(1000.0, std::min(0.8 * half_length / std::tan(fov / 2),
                                                    0.7 * height / std::tan(half_vfov)));
  // Beside the walk's line, within 0.3 m of its middle, turned up to 10 degrees along it.
  const Eigen::Vector2d foot = centre + (600 * u(*rng) - 300) * walk;
  const Eigen::Vector2d at = foot + distance * side;
  const double turn = (20 * u(*rng) - 10) * kDeg;
  const Eigen::Vector2d look = -side * std::cos(turn) + walk * std::sin(turn);
  const Eigen::Vector2d target = at + distance * look;
  Camera camera = LookAtCamera("cam0", options.Width(), options.Height(), 1.0, {at.x(), height, at.y()},
                               {target.x(), 900 + 300 * u(*rng), target.y()});
  camera.fx = camera.fy = options.Width() / 2.0 / std::tan(fov / 2);
  return {camera};
}

}  // namespace

std::string_view RigKindName(RigKind kind) {
  switch (kind) {
    case RigKind::kRing: return "ring";
    case RigKind::kSurveillance: return "surveillance";
    case RigKind::kWebcam: return "webcam";
  }
  return "?";
}

bool ParseRigKind(std::string_view name, RigKind* kind) {
  return ParseByName(name, {RigKind::kRing, RigKind::kSurveillance, RigKind::kWebcam}, RigKindName, kind);
}

int RigOptions::Width() const { return width > 0 ? width : kind == RigKind::kRing ? 320 : 640; }
int RigOptions::Height() const { return height > 0 ? height : kind == RigKind::kRing ? 240 : 480; }

bool RigOptions::Check(std::string* why) const {
  auto fail = [&](const std::string& what) { if (why) *why = what; return false; };
  if (num_cameras < 1 || num_cameras > 4) return fail("cameras: expected 1 to 4");
  if (kind == RigKind::kWebcam && num_cameras != 1) return fail("cameras: the webcam rig has one camera");
  if ((width != 0 && (width < 32 || width > 4096)) || (height != 0 && (height < 32 || height > 4096)))
    return fail("image size: expected 32 to 4096 pixels a side");
  if (!(ring_radius_mm >= 1000 && ring_radius_mm <= 50000)) return fail("ring radius: expected 1000 to 50000 mm");
  if (!(camera_height_mm > 0 && camera_height_mm < 10000)) return fail("camera height: expected 0 to 10000 mm");
  return true;
}

std::vector<Camera> DefaultRig(const std::vector<Eigen::Matrix3Xd>& joints, const RigOptions& options) {
  JGPM_CHECK(!joints.empty() && options.Check(nullptr));
  Eigen::Vector2d centre, walk;
  Walk(joints, &centre, &walk);
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
    Camera camera = LookAtCamera("cam" + std::to_string(cameras.size()), options.Width(), options.Height(),
                                 1.0, {at.x(), options.camera_height_mm, at.y()},
                                 {centre.x(), 1000, centre.y()});
    camera.fx = camera.fy = LargestFocalInView(camera, joints);
    cameras.push_back(camera);
  }
  return cameras;
}

std::vector<Camera> MakeRig(const std::vector<Eigen::Matrix3Xd>& joints, const RigOptions& options, uint64_t seed) {
  JGPM_CHECK(!joints.empty() && options.Check(nullptr));
  std::mt19937_64 rng(seed * 0x9E3779B97F4A7C15ull + 0xC0FFEE);
  switch (options.kind) {
    case RigKind::kRing: return DefaultRig(joints, options);
    case RigKind::kSurveillance: return SurveillanceRig(joints, options, &rng);
    case RigKind::kWebcam: return WebcamRig(joints, options, &rng);
  }
  return {};
}

Camera Miscalibrate(const Camera& camera, double scale, std::mt19937_64* rng) {
  if (scale <= 0) return camera;
  std::uniform_real_distribution<double> u(-1, 1);
  std::normal_distribution<double> normal(0, 1);
  auto unit = [&] {
    Eigen::Vector3d d(normal(*rng), normal(*rng), normal(*rng));
    return d.norm() > 1e-9 ? Eigen::Vector3d(d.normalized()) : Eigen::Vector3d::UnitX();
  };
  Camera c = camera;
  const double focal = 1 + 0.015 * scale * u(*rng);
  c.fx *= focal;
  c.fy *= focal;
  c.cx += 4 * scale * u(*rng);
  c.cy += 4 * scale * u(*rng);
  // The camera turned about its own centre and moved: the centre stays where it was moved to.
  const Eigen::Vector3d centre = camera.CentreInWorld() + 30 * scale * std::abs(u(*rng)) * unit();
  const Eigen::Matrix3d turn = Eigen::AngleAxisd(0.7 * kDeg * scale * u(*rng), unit()).toRotationMatrix();
  c.cam_from_world_rotation = turn * camera.cam_from_world_rotation;
  c.cam_from_world_translation_mm = -c.cam_from_world_rotation * centre;
  return c;
}

}  // namespace jgpm
