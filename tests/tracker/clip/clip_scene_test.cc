// The scene around a synthetic walker, against oracles: box hits against marching along
// the ray, a sphere's shadow against the analytic one, occluders where they are said to
// stand (off the walk, between a camera and it) and drawn where the camera sees them.
#include "tracker/clip/clip_scene.h"

#include <cmath>
#include <limits>
#include <numbers>
#include <random>

#include <Eigen/Geometry>
#include <gtest/gtest.h>
#include <opencv2/core.hpp>

namespace jgpm {
namespace {

// Is the point inside the box?
bool Inside(const SceneBox& b, const Eigen::Vector3d& p) {
  const Eigen::Vector3d local = b.axes.transpose() * (p - b.centre_mm);
  return (local.cwiseAbs() - b.half_mm).maxCoeff() <= 0;
}

TEST(IntersectBox, AgreesWithMarchingAlongTheRay) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1, 1);
  SceneBox box;
  box.centre_mm = {100, 700, -50};
  box.axes = Eigen::AngleAxisd(0.6, Eigen::Vector3d(1, 2, 0.5).normalized()).toRotationMatrix();
  box.half_mm = {300, 40, 200};
  int hits = 0;
  for (int trial = 0; trial < 400; ++trial) {
    const Eigen::Vector3d origin(2000 * u(rng), 700 + 1500 * u(rng), 2000 * u(rng));
    const Eigen::Vector3d aim = box.centre_mm + Eigen::Vector3d(400 * u(rng), 100 * u(rng), 400 * u(rng));
    const Eigen::Vector3d direction = (aim - origin).normalized();
    // The oracle: the first of 0.1 mm steps inside the box.
    double first = -1;
    for (double t = 0; t < 5000; t += 0.1) {
      if (Inside(box, origin + t * direction)) {
        first = t;
        break;
      }
    }
    double t = 0;
    Eigen::Vector3d normal;
    const bool hit = IntersectBox(origin, direction, box, &t, &normal);
    if (first < 0 || Inside(box, origin)) {
      if (first < 0) { EXPECT_FALSE(hit) << trial; }
      continue;
    }
    ASSERT_TRUE(hit) << trial;
    EXPECT_NEAR(t, first, 0.1) << trial;
    EXPECT_NEAR(normal.norm(), 1.0, 1e-12);
    EXPECT_LT(normal.dot(direction), 0) << trial;  // outward, against the ray
    ++hits;
  }
  EXPECT_GT(hits, 100);
}

// A camera looking down at the floor about the origin from 3 m up and 3 m away.
Camera FloorCamera() {
  return LookAtCamera("cam0", 160, 120, 150, {0, 3000, -3000}, {0, 0, 0});
}

TEST(ClipScene, ASpheresShadowIsTheAnalyticOne) {
  const Camera camera = FloorCamera();
  SceneOptions options;
  options.shadow = true;
  // Any walk: the scene has no occluders, only the light.
  const std::vector<Eigen::Matrix3Xd> walk = {Eigen::Matrix3Xd::Zero(3, 1)};
  const ClipScene scene(options, {camera}, walk, 5);
  const Eigen::Vector3d light = scene.light();
  EXPECT_NEAR(light.norm(), 1, 1e-12);
  const double elevation = std::asin(light.y()) * 180 / std::numbers::pi;
  EXPECT_GE(elevation, 35);
  EXPECT_LE(elevation, 65);
  EXPECT_GE(scene.shadow_gain(), 0.4);
  EXPECT_LE(scene.shadow_gain(), 0.6);
  // A ball of 300 mm radius 700 mm above the origin.
  const Eigen::Vector3d centre(0, 700, 0);
  const std::vector<Capsule> body = {{centre, centre, 300, 300}};
  const RayCaster caster(camera);
  cv::Mat objects_depth(camera.height, camera.width, CV_32F, cv::Scalar(std::numeric_limits<float>::infinity()));
  cv::Mat floor, shadow;
  ClipScene::VisibleFloor(caster, objects_depth, Eigen::Vector3d::Zero(), 12000, &floor);
  scene.RenderShadow(caster, body, floor, &shadow);
  // Oracle: the floor point's ray to the light passes within the radius of the centre.
  int agree = 0, shadowed = 0, disagree = 0;
  const Eigen::Vector3d eye = camera.CentreInWorld();
  for (int v = 0; v < camera.height; ++v)
    for (int u = 0; u < camera.width; ++u) {
      const Eigen::Vector3d ray = caster.rays().col(v * camera.width + u);
      bool expected = false;
      if (ray.y() < 0) {
        const Eigen::Vector3d p = eye - eye.y() / ray.y() * ray;
        const Eigen::Vector3d to_centre = centre - p;
        const double along = to_centre.dot(light);
        expected = along > 0 && (to_centre - along * light).norm() < 300;
      }
      const bool got = shadow.at<uint8_t>(v, u) != 0;
      (got == expected ? agree : disagree) += 1;
      shadowed += got;
    }
  EXPECT_GT(shadowed, 50);
  EXPECT_EQ(disagree, 0);
  // No shadow without the option.
  const ClipScene unlit({}, {camera}, walk, 5);
  unlit.RenderShadow(caster, body, floor, &shadow);
  EXPECT_EQ(cv::countNonZero(shadow), 0);
}

TEST(ClipScene, OccludersStandBetweenTheCamerasAndTheWalkOffItsPath) {
  // A straight walk of 4 m along +z; two cameras 5 m to its sides.
  std::vector<Eigen::Matrix3Xd> walk;
  for (int k = 0; k < 60; ++k) {
    Eigen::Matrix3Xd j = Eigen::Matrix3Xd::Zero(3, 2);
    j.col(0) << 0, 900, -2000 + 4000.0 * k / 59;
    j.col(1) << 0, 1700, -2000 + 4000.0 * k / 59;
    walk.push_back(j);
  }
  const std::vector<Camera> cameras = {LookAtCamera("cam0", 320, 240, 250, {5000, 1500, 0}, {0, 1000, 0}),
                                       LookAtCamera("cam1", 320, 240, 250, {-5000, 1500, 0}, {0, 1000, 0})};
  SceneOptions options;
  options.occluders = 4;
  for (uint64_t seed = 1; seed <= 5; ++seed) {
    const ClipScene scene(options, cameras, walk, seed);
    ASSERT_EQ(scene.objects().size(), 4u) << seed;
    for (size_t i = 0; i < scene.objects().size(); ++i) {
      const SceneObject& o = scene.objects()[i];
      // Every part's floor position: nearer camera i % 2 than the walk is, and off the path.
      const double camera_x = cameras[i % 2].CentreInWorld().x();
      std::vector<Eigen::Vector3d> points;
      for (const SceneBox& b : o.boxes) points.push_back(b.centre_mm);
      for (const Capsule& c : o.capsules) points.push_back(c.from_mm);
      ASSERT_FALSE(points.empty());
      for (const Eigen::Vector3d& q : points) {
        EXPECT_GT(std::abs(q.x()), 300) << o.kind;       // not on the walk's line (x = 0)
        EXPECT_LT(std::abs(q.x()), 5000) << o.kind;      // nearer than the camera
        EXPECT_GT(q.x() * camera_x, 0) << o.kind;        // on that camera's side
        EXPECT_GE(q.y(), 0) << o.kind;                   // on the floor, not in it
      }
    }
    // Each camera sees its objects: drawn, with depths where the boxes and capsules are.
    const RayCaster caster(cameras[0]);
    cv::Mat depth, colour;
    scene.RenderObjects(caster, &depth, &colour);
    EXPECT_GT(cv::countNonZero(depth < std::numeric_limits<float>::infinity()), 200) << seed;
    for (int v = 0; v < depth.rows; v += 7)
      for (int u = 0; u < depth.cols; u += 7) {
        const float d = depth.at<float>(v, u);
        if (!std::isfinite(d)) continue;
        const Eigen::Vector3d p = caster.centre_in_world_mm() + d * caster.rays().col(v * depth.cols + u);
        double nearest = 1e9;  // the point lies on some part's surface
        for (const SceneObject& o : scene.objects()) {
          for (const SceneBox& b : o.boxes) {
            const Eigen::Vector3d local = (b.axes.transpose() * (p - b.centre_mm)).cwiseAbs() - b.half_mm;
            nearest = std::min(nearest, std::abs(local.maxCoeff()));
          }
          for (const Capsule& c : o.capsules) {
            const Eigen::Vector3d ab = c.to_mm - c.from_mm;
            const double s = std::clamp((p - c.from_mm).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
            nearest = std::min(nearest, std::abs((p - c.from_mm - s * ab).norm() - c.radius_from_mm));
          }
        }
        EXPECT_LT(nearest, 1.0) << u << "," << v;
      }
  }
}

}  // namespace
}  // namespace jgpm
