// The light found from masks that hold a walker's shadow against the light that cast it
// (ray-cast, shadow_oracle.h), scored with the true body as the tracker scores its estimate; and no
// light from masks without a shadow, nor from clutter beside the feet.
#include "tracker/filter/shadow_light.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "io/mocap/amc.h"
#include "io/mocap/asf.h"
#include "io/mocap/kinematics.h"
#include "test_support.h"
#include "tracker/body/body_model.h"
#include "tracker/body/ray_caster.h"
#include "tracker/body/shadow_oracle.h"
#include "tracker/filter/likelihood.h"

namespace jgpm {
namespace {

struct Scene {
  Skeleton skeleton;
  Motion motion;
  std::vector<Camera> cameras;
  double floor_mm = 0;  // the lowest foot's height over the frames used
};

constexpr int kFirst = 100, kStep = 3, kFrames = 40;

const Scene& Walk() {
  static const Scene scene = [] {
    Scene s;
    s.skeleton = ReadAsf(test::CmuRoot() / "subjects/35/35.asf");
    s.motion = ReadAmc(test::CmuRoot() / "subjects/35/35_01.amc", s.skeleton);
    const Kinematics kinematics(s.skeleton);
    s.floor_mm = 1e9;
    for (int k = 0; k < kFrames; ++k)
      s.floor_mm = std::min(s.floor_mm, kinematics.Compute(s.motion.Frame(kFirst + k * kStep)).row(1).minCoeff());
    s.floor_mm -= 30;  // a foot's radius below its joint
    const Eigen::Matrix3Xd middle = kinematics.Compute(s.motion.Frame(kFirst + kFrames * kStep / 2));
    const Eigen::Vector3d at(middle(0, 0), s.floor_mm + 900, middle(2, 0));
    // A camera at eye level beside the walk and one 5 m up in front of it.
    s.cameras.push_back(LookAtCamera("side", 240, 180, 250, at + Eigen::Vector3d(5000, 600, 0), at));
    s.cameras.push_back(LookAtCamera("high", 240, 180, 300, at + Eigen::Vector3d(1500, 4100, 6000), at));
    return s;
  }();
  return scene;
}

std::vector<Capsule> Body(const Scene& s, int frame) {
  return BodyModel(s.skeleton, {}, "35.asf").Place(Kinematics(s.skeleton).Compute(s.motion.Frame(frame)));
}

// The body's exact silhouette, its shadow under `light` (when given) and `clutter` (discs,
// floor points with radii in mm, drawn as the floor's ellipses seen from the camera).
cv::Mat Mask(const Scene& s, const Camera& camera, const std::vector<Capsule>& body, const Eigen::Vector3d* light,
             const std::vector<Eigen::Vector3d>& clutter = {}) {
  BodyImage image;
  RayCaster(camera).Render(body, &image);
  cv::Mat mask = image.Mask();
  if (light) test::AddRayCastShadow(camera, body, *light, s.floor_mm, &mask, body.front().from_mm, 4000);
  if (!clutter.empty()) {
    const Eigen::Matrix3Xd floor = test::FloorPoints(camera, s.floor_mm);
    for (int i = 0; i < floor.cols(); ++i)
      for (const Eigen::Vector3d& disc : clutter)
        if (Eigen::Vector2d(floor(0, i) - disc.x(), floor(2, i) - disc.y()).norm() < disc.z())
          mask.at<uchar>(i / camera.width, i % camera.width) = 255;
  }
  return mask;
}

// Looks at every frame (the tracker looks every `every`-th) until a light is found; the
// number of looks made.
int Find(const Scene& s, ShadowLight* finder, const Eigen::Vector3d* light, double clutter_mm = 0) {
  SilhouetteLikelihood likelihood(s.cameras);
  likelihood.SetShadow(std::nullopt, s.floor_mm);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int k = 0; k < kFrames; ++k) {
    const std::vector<Capsule> body = Body(s, kFirst + k * kStep);
    std::vector<Eigen::Vector3d> clutter;
    if (clutter_mm > 0) {
      // Two discs on the floor within a metre of the feet, somewhere else each frame.
      const Eigen::Vector3d& root = body.front().from_mm;
      for (int i = 0; i < 2; ++i)
        clutter.emplace_back(root.x() + 1000 * u(rng), root.z() + 1000 * u(rng), clutter_mm);
    }
    std::vector<CameraObservation> observations;
    for (const Camera& camera : s.cameras) {
      const cv::Mat mask = Mask(s, camera, body, light, clutter);
      cv::Rect box = cv::boundingRect(mask);
      observations.push_back(likelihood.Observe(mask, cv::Rect(box.x - 10, box.y - 10, box.width + 20, box.height + 20)));
    }
    finder->Look([&](const std::vector<std::optional<Eigen::Vector3d>>& lights) {
      SilhouetteLikelihood::Workspace workspace = likelihood.NewWorkspace();
      std::vector<double> costs;
      for (const auto& l : lights) costs.push_back(likelihood.CostUnder(l ? &*l : nullptr, body, observations, &workspace));
      return costs;
    });
    if (finder->light()) return k + 1;
  }
  return kFrames;
}

double DegreesBetween(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::acos(std::clamp(a.normalized().dot(b.normalized()), -1.0, 1.0)) * 180 / std::numbers::pi;
}

TEST(ShadowLight, FindsTheLightThatCastTheShadowInTheMasks) {
  const Scene& s = Walk();
  for (const auto& [azimuth, elevation] : {std::pair{235.0, 62.0}, {40.0, 33.0}, {130.0, 48.0}}) {
    SCOPED_TRACE("azimuth " + std::to_string(azimuth) + " elevation " + std::to_string(elevation));
    const Eigen::Vector3d light = ShadowLight::Direction(azimuth, elevation);
    ShadowLight finder;
    const int looks = Find(s, &finder, &light);
    ASSERT_TRUE(finder.light().has_value());
    // The coarse grid's six looks and the fine grid's six.
    EXPECT_EQ(looks, 12);
    // Within the fine grid's 3 degrees either way in azimuth and elevation.
    EXPECT_LT(DegreesBetween(*finder.light(), light), 4.5);
  }
}

TEST(ShadowLight, FindsNoLightWithoutAShadowNorInClutterBesideTheFeet) {
  const Scene& s = Walk();
  ShadowLight bare;
  Find(s, &bare, nullptr);
  EXPECT_FALSE(bare.light().has_value());
  // Discs 0.3 m across, as large as a leg's shadow, within a metre of the feet.
  ShadowLight cluttered;
  Find(s, &cluttered, nullptr, 150);
  EXPECT_FALSE(cluttered.light().has_value());
}

// A shadow out of sight for the first looks (the walker's feet behind a table, the
// shadow with them) and in sight after: the light is judged on the last `looks` looks, so
// the looks that could not see it do not outweigh those that do. The costs are made up:
// a light gains 0.12 at the true one, falling to nothing 20 degrees away, from look 9 on.
// Found after 18 looks (the coarse grid's last six at look 12, four of them seeing it; the
// fine grid's six); before, with the mean over every look since the grid was set, 26.
TEST(ShadowLight, AShadowSeenOnlyAfterSomeLooksIsFoundOnTheLooksThatSeeIt) {
  const Eigen::Vector3d light = ShadowLight::Direction(200, 55);
  ShadowLight finder;
  int looks = 0;
  while (!finder.light() && looks < 40) {
    const bool seen = ++looks > 8;
    finder.Look([&](const std::vector<std::optional<Eigen::Vector3d>>& lights) {
      std::vector<double> costs{1.0};
      for (size_t i = 1; i < lights.size(); ++i)
        costs.push_back(1.0 - (seen ? 0.12 * std::max(0.0, 1 - DegreesBetween(*lights[i], light) / 20) : 0.0));
      return costs;
    });
  }
  ASSERT_TRUE(finder.light().has_value());
  EXPECT_LE(looks, 8 + 6 + 6);
  EXPECT_LT(DegreesBetween(*finder.light(), light), 2.2);  // the fine grid's nearest point
}

TEST(ShadowLight, LooksEveryFewFramesThenRarelyWhenNothingIsFound) {
  ShadowLightOptions options;
  options.every = 5, options.idle_after = 3, options.idle_every = 20;
  ShadowLight finder(options);
  std::vector<int> due;
  const auto nothing = [](const std::vector<std::optional<Eigen::Vector3d>>& lights) {
    std::vector<double> costs(lights.size(), 1.0);
    costs[0] = 0.5;  // no shadow explains the masks best
    return costs;
  };
  for (int frame = 0; frame < 80; ++frame)
    if (finder.Due()) {
      due.push_back(frame);
      finder.Look(nothing);
    }
  EXPECT_EQ(due, (std::vector<int>{0, 5, 10, 20, 40, 60}));
  EXPECT_FALSE(finder.light().has_value());
}

}  // namespace
}  // namespace jgpm
