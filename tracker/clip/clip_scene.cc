#include "tracker/clip/clip_scene.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>

#include <opencv2/core.hpp>

#include "io/base/error.h"

namespace jgpm {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Objects are lit from above and a side, as the walker is in synthetic_clip.cc.
const Eigen::Vector3d& ObjectLight() {
  static const Eigen::Vector3d light = Eigen::Vector3d(-0.3, 1.0, -0.4).normalized();
  return light;
}

SceneBox Box(const Eigen::Vector3d& centre, double yaw, const Eigen::Vector3d& half) {
  SceneBox b;
  b.centre_mm = centre;
  b.axes << std::cos(yaw), 0, std::sin(yaw), 0, 1, 0, -std::sin(yaw), 0, std::cos(yaw);
  b.half_mm = half;
  return b;
}

Capsule Rod(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double radius) {
  return {a, b, radius, radius};
}

// An object of `kind` standing at floor point (x, z), turned by `yaw`.
SceneObject MakeObject(const std::string& kind, double x, double z, double yaw, std::mt19937_64* rng) {
  std::uniform_real_distribution<double> u(0, 1);
  SceneObject o;
  o.kind = kind;
  const Eigen::Vector3d at(x, 0, z);
  const Eigen::Vector3d along(std::cos(yaw), 0, -std::sin(yaw)), across(std::sin(yaw), 0, std::cos(yaw));
  if (kind == "pillar") {
    const double half = 150 + 100 * u(*rng);
    o.boxes.push_back(Box(at + Eigen::Vector3d(0, 1300, 0), yaw, {half, 1300, half}));
    const float grey = static_cast<float>(150 + 40 * u(*rng));
    o.colour_bgr = {grey, grey, grey * 1.02f};
  } else if (kind == "table") {
    o.boxes.push_back(Box(at + Eigen::Vector3d(0, 710, 0), yaw, {600, 20, 350}));
    for (double sa : {-1.0, 1.0})
      for (double sc : {-1.0, 1.0}) {
        const Eigen::Vector3d leg = at + sa * 550 * along + sc * 300 * across + Eigen::Vector3d(0, 345, 0);
        o.boxes.push_back(Box(leg, yaw, {20, 345, 20}));
      }
    o.colour_bgr = {static_cast<float>(40 + 30 * u(*rng)), static_cast<float>(80 + 30 * u(*rng)),
                    static_cast<float>(120 + 40 * u(*rng))};
  } else {  // bicycle, on its wheels, its frame along `along`
    constexpr double kWheel = 340, kTube = 16;
    const Eigen::Vector3d rear = at - 520 * along + Eigen::Vector3d(0, kWheel, 0);
    const Eigen::Vector3d front = at + 520 * along + Eigen::Vector3d(0, kWheel, 0);
    for (const Eigen::Vector3d& hub : {rear, front}) {
      constexpr int kSegments = 14;
      for (int s = 0; s < kSegments; ++s) {
        const double a0 = 2 * std::numbers::pi * s / kSegments, a1 = 2 * std::numbers::pi * (s + 1) / kSegments;
        auto rim = [&](double a) { return Eigen::Vector3d(hub + kWheel * (std::cos(a) * along + std::sin(a) * Eigen::Vector3d::UnitY())); };
        o.capsules.push_back(Rod(rim(a0), rim(a1), 18));
      }
    }
    const Eigen::Vector3d crank = at + Eigen::Vector3d(0, 300, 0), seat = at - 180 * along + Eigen::Vector3d(0, 900, 0);
    const Eigen::Vector3d head = at + 380 * along + Eigen::Vector3d(0, 850, 0);
    for (const auto& [a, b] : {std::pair{rear, crank}, std::pair{crank, seat}, std::pair{seat, rear},
                               std::pair{seat, head}, std::pair{crank, head}, std::pair{head, front}}) {
      o.capsules.push_back(Rod(a, b, kTube));
    }
    o.capsules.push_back(Rod(seat - 100 * along + Eigen::Vector3d(0, 40, 0), seat + 120 * along + Eigen::Vector3d(0, 40, 0), 45));
    const Eigen::Vector3d bar = head + Eigen::Vector3d(0, 150, 0);
    o.capsules.push_back(Rod(head, bar, kTube));
    o.capsules.push_back(Rod(bar - 280 * across, bar + 280 * across, 14));
    o.colour_bgr = {static_cast<float>(30 + 60 * u(*rng)), static_cast<float>(30 + 40 * u(*rng)),
                    static_cast<float>(60 + 150 * u(*rng))};
  }
  return o;
}

// How far from its place an object reaches on the floor, mm.
double Footprint(const std::string& kind) { return kind == "pillar" ? 360 : kind == "table" ? 700 : 900; }

// The bounding sphere of an object's parts.
void Bound(const SceneObject& o, Eigen::Vector3d* centre, double* radius) {
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(kInf), hi = -lo;
  for (const Capsule& c : o.capsules) {
    const double r = std::max(c.radius_from_mm, c.radius_to_mm);
    lo = lo.cwiseMin(c.from_mm.cwiseMin(c.to_mm) - Eigen::Vector3d::Constant(r));
    hi = hi.cwiseMax(c.from_mm.cwiseMax(c.to_mm) + Eigen::Vector3d::Constant(r));
  }
  for (const SceneBox& b : o.boxes) {
    const Eigen::Vector3d extent = b.axes.cwiseAbs() * b.half_mm;
    lo = lo.cwiseMin(b.centre_mm - extent);
    hi = hi.cwiseMax(b.centre_mm + extent);
  }
  *centre = 0.5 * (lo + hi);
  *radius = 0.5 * (hi - lo).norm();
}

}  // namespace

bool SceneOptions::Check(std::string* why) const {
  if (occluders < 0 || occluders > 8) {
    if (why) *why = "occluders: expected 0 to 8";
    return false;
  }
  if (!(reflection >= 0 && reflection <= 0.5)) {
    if (why) *why = "reflection: expected 0 to 0.5";
    return false;
  }
  return true;
}

std::vector<Capsule> MirroredInFloor(std::vector<Capsule> capsules) {
  for (Capsule& c : capsules) {
    c.from_mm.y() = -c.from_mm.y();
    c.to_mm.y() = -c.to_mm.y();
  }
  return capsules;
}

void ClipScene::VisibleFloor(const RayCaster& caster, const cv::Mat& objects_depth,
                             const Eigen::Vector3d& room_centre_mm, double room_radius_mm, cv::Mat* floor) {
  const Camera& camera = caster.camera();
  floor->create(camera.height, camera.width, CV_8U);
  floor->setTo(0);
  const Eigen::Vector3d& origin = caster.centre_in_world_mm();
  if (origin.y() <= 0) return;
  for (int v = 0; v < camera.height; ++v) {
    uint8_t* out = floor->ptr<uint8_t>(v);
    const float* objects = objects_depth.ptr<float>(v);
    for (int w = 0; w < camera.width; ++w) {
      const Eigen::Vector3d ray = caster.rays().col(static_cast<Eigen::Index>(v) * camera.width + w);
      if (ray.y() >= -1e-9) continue;
      const double t = -origin.y() / ray.y();
      if (t >= objects[w]) continue;
      const Eigen::Vector3d p = origin + t * ray;
      if (Eigen::Vector2d(p.x() - room_centre_mm.x(), p.z() - room_centre_mm.z()).norm() < room_radius_mm) out[w] = 255;
    }
  }
}

bool IntersectBox(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction, const SceneBox& box, double* t,
                  Eigen::Vector3d* normal) {
  // Slabs in the box's frame.
  const Eigen::Vector3d o = box.axes.transpose() * (origin - box.centre_mm);
  const Eigen::Vector3d d = box.axes.transpose() * direction;
  double near = -kInf, far = kInf;
  int axis = 0;
  double sign = 1;
  for (int k = 0; k < 3; ++k) {
    if (std::abs(d[k]) < 1e-12) {
      if (std::abs(o[k]) > box.half_mm[k]) return false;
      continue;
    }
    double t0 = (-box.half_mm[k] - o[k]) / d[k], t1 = (box.half_mm[k] - o[k]) / d[k];
    double s = -1;  // entering through the -k face
    if (t0 > t1) std::swap(t0, t1), s = 1;
    if (t0 > near) near = t0, axis = k, sign = s;
    far = std::min(far, t1);
  }
  if (near > far || far < 0) return false;
  *t = std::max(near, 0.0);
  if (normal) *normal = box.axes.col(axis) * sign;
  return true;
}

ClipScene::ClipScene(const SceneOptions& options, const std::vector<Camera>& cameras,
                     const std::vector<Eigen::Matrix3Xd>& joints, uint64_t seed)
    : options_(options) {
  std::string why;
  if (!options.Check(&why)) ThrowInputError("render options", why);
  JGPM_CHECK(!cameras.empty() && !joints.empty());
  std::mt19937_64 rng(seed * 0x2545F4914F6CDD1Dull + 0x51);
  std::uniform_real_distribution<double> u(0, 1);
  {
    const double elevation = (35 + 30 * u(rng)) * std::numbers::pi / 180, azimuth = 2 * std::numbers::pi * u(rng);
    light_ = Eigen::Vector3d(std::cos(elevation) * std::sin(azimuth), std::sin(elevation),
                             std::cos(elevation) * std::cos(azimuth));
    shadow_gain_ = 0.4 + 0.2 * u(rng);
  }
  std::vector<Eigen::Vector2d> path;
  for (const Eigen::Matrix3Xd& j : joints) path.emplace_back(j(0, 0), j(2, 0));
  auto clearance = [&](const Eigen::Vector2d& q) {
    double nearest = kInf;
    for (const Eigen::Vector2d& p : path) nearest = std::min(nearest, (p - q).norm());
    return nearest;
  };
  static const char* kKinds[] = {"pillar", "table", "bicycle"};
  for (int i = 0; i < options.occluders; ++i) {
    const Camera& camera = cameras[i % cameras.size()];
    const Eigen::Vector3d eye = camera.CentreInWorld();
    const Eigen::Vector2d c(eye.x(), eye.z());
    std::string kind = kKinds[static_cast<int>(3 * u(rng)) % 3];
    bool placed = false;
    for (int attempt = 0; attempt < 80 && !placed; ++attempt) {
      if (attempt == 40) kind = "pillar";  // the smallest, when nothing bigger fits
      const Eigen::Vector2d p = path[static_cast<size_t>(u(rng) * path.size()) % path.size()];
      const Eigen::Vector2d q = c + (0.55 + 0.3 * u(rng)) * (p - c);
      const double yaw = 2 * std::numbers::pi * u(rng);
      // Off the walk (the walker's half-width, ~0.3 m, and a margin) and off the camera.
      if (clearance(q) < Footprint(kind) + 400 || (q - c).norm() < Footprint(kind) + 300) continue;
      objects_.push_back(MakeObject(kind, q.x(), q.y(), yaw, &rng));
      placed = true;
    }
  }
}

void ClipScene::RenderObjects(const RayCaster& caster, cv::Mat* depth_mm, cv::Mat* colour) const {
  const Camera& camera = caster.camera();
  depth_mm->create(camera.height, camera.width, CV_32F);
  colour->create(camera.height, camera.width, CV_32FC3);
  depth_mm->setTo(std::numeric_limits<float>::infinity());
  colour->setTo(cv::Scalar::all(0));
  if (objects_.empty()) return;
  const Eigen::Vector3d& origin = caster.centre_in_world_mm();
  std::vector<Eigen::Vector3d> centres(objects_.size());
  std::vector<double> radii(objects_.size());
  for (size_t i = 0; i < objects_.size(); ++i) Bound(objects_[i], &centres[i], &radii[i]);
  for (int v = 0; v < camera.height; ++v) {
    float* depth = depth_mm->ptr<float>(v);
    cv::Vec3f* out = colour->ptr<cv::Vec3f>(v);
    for (int w = 0; w < camera.width; ++w) {
      const Eigen::Vector3d ray = caster.rays().col(static_cast<Eigen::Index>(v) * camera.width + w);
      double nearest = kInf;
      Eigen::Vector3d normal;
      const SceneObject* hit = nullptr;
      for (size_t i = 0; i < objects_.size(); ++i) {
        const Eigen::Vector3d oc = centres[i] - origin;
        const double along = oc.dot(ray);
        if (oc.squaredNorm() - along * along > radii[i] * radii[i]) continue;
        double t;
        Eigen::Vector3d n;
        for (const Capsule& c : objects_[i].capsules)
          if (IntersectCapsule(origin, ray, c, &t, &n) && t < nearest) nearest = t, normal = n, hit = &objects_[i];
        for (const SceneBox& b : objects_[i].boxes)
          if (IntersectBox(origin, ray, b, &t, &n) && t < nearest) nearest = t, normal = n, hit = &objects_[i];
      }
      if (!hit) continue;
      depth[w] = static_cast<float>(nearest);
      const double lambert = std::max(0.0, ObjectLight().dot(normal));
      out[w] = hit->colour_bgr * static_cast<float>(0.4 + 0.6 * lambert);
    }
  }
}

void ClipScene::RenderShadow(const RayCaster& caster, const std::vector<Capsule>& body, const cv::Mat& floor,
                             cv::Mat* shadow) const {
  const Camera& camera = caster.camera();
  shadow->create(camera.height, camera.width, CV_8U);
  shadow->setTo(0);
  if (!options_.shadow || body.empty() || light_.y() <= 0) return;
  // The shadow's bounds on the floor: every part's ends cast along the light, grown by its
  // radius stretched as a sphere's shadow is (1 / sin elevation).
  Eigen::Vector2d lo(kInf, kInf), hi(-kInf, -kInf);
  for (const Capsule& c : body) {
    for (const auto& [p, r] : {std::pair{c.from_mm, c.radius_from_mm}, std::pair{c.to_mm, c.radius_to_mm}}) {
      const Eigen::Vector3d f = p - (p.y() / light_.y()) * light_;
      const double grow = r / light_.y() + r;
      lo = lo.cwiseMin(Eigen::Vector2d(f.x(), f.z()) - Eigen::Vector2d::Constant(grow));
      hi = hi.cwiseMax(Eigen::Vector2d(f.x(), f.z()) + Eigen::Vector2d::Constant(grow));
    }
  }
  const Eigen::Vector3d& origin = caster.centre_in_world_mm();
  for (int v = 0; v < camera.height; ++v) {
    uint8_t* out = shadow->ptr<uint8_t>(v);
    const uint8_t* on_floor = floor.ptr<uint8_t>(v);
    for (int w = 0; w < camera.width; ++w) {
      if (!on_floor[w]) continue;
      const Eigen::Vector3d ray = caster.rays().col(static_cast<Eigen::Index>(v) * camera.width + w);
      const Eigen::Vector3d p = origin + (-origin.y() / ray.y()) * ray;
      if (p.x() < lo.x() || p.x() > hi.x() || p.z() < lo.y() || p.z() > hi.y()) continue;
      double hit;
      for (const Capsule& c : body) {
        if (IntersectCapsule(p, light_, c, &hit, nullptr)) {
          out[w] = 255;
          break;
        }
      }
    }
  }
}

}  // namespace jgpm
