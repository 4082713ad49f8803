// The build's fit against oracles: on a cost whose minimum is known it goes there, and on
// exact silhouettes of a walker of another build (the ray caster; other widths, shorter
// legs, longer arms, on a floor higher than the cameras have it) it finds that build.
#include "tracker/filter/body_shape.h"

#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "io/mocap/amc.h"
#include "io/mocap/asf.h"
#include "io/mocap/kinematics.h"
#include "test_support.h"
#include "tracker/body/ray_caster.h"
#include "tracker/filter/likelihood.h"
#include "tracker/state/proportions.h"

namespace jgpm {
namespace {

TEST(BodyShapeTest, GoesToAQuadraticsMinimumRelativeToTheTorso) {
  Build best;
  best.widths = {1.0, 0.8, 1.03, 1.25, 0.9};
  best.lengths = {0.93, 1.06};
  const RegionScales weight = {1, 3, 0.5, 2, 1};
  int calls = 0;
  const auto cost = [&](const Build& b) {
    ++calls;
    double sum = 0;
    for (int r = 0; r < kNumBodyRegions; ++r) sum += weight[r] * std::pow(std::log(b.widths[r] / best.widths[r]), 2);
    return sum + 5 * std::pow(std::log(b.lengths.legs / best.lengths.legs), 2) +
           std::pow(std::log(b.lengths.arms / best.lengths.arms), 2) + 1e-4 * std::pow(b.floor_mm - best.floor_mm, 2);
  };
  best.floor_mm = 45;
  BodyShape shape;
  shape.Update(cost, true);
  EXPECT_EQ(calls, 1 + 2 * (kNumBodyRegions - 1 + 2 + 1));
  EXPECT_NEAR(shape.build().floor_mm, 0.1 * 20, 1e-9);  // a tenth of one probe (20 mm)
  // One update moves each scale a tenth of the way in the logarithm (the parabola of a
  // quadratic is exact, but a step is at most one probe); the torso stays.
  const auto first_step = [](double target, double probe) {
    return 0.1 * std::clamp(std::log(target), -std::log1p(probe), std::log1p(probe));
  };
  for (int r = 0; r < kNumBodyRegions; ++r)
    EXPECT_NEAR(std::log(shape.build().widths[r]), r == 0 ? 0 : first_step(best.widths[r], 0.1), 1e-9) << r;
  EXPECT_NEAR(std::log(shape.build().lengths.legs), first_step(0.93, 0.04), 1e-9);
  EXPECT_NEAR(std::log(shape.build().lengths.arms), first_step(1.06, 0.04), 1e-9);
  for (int i = 0; i < 300; ++i) shape.Update(cost, true);
  EXPECT_NEAR(shape.build().floor_mm, 45, 1e-3);
  // Seen by one camera only, the floor stays where it is.
  calls = 0;
  shape.Update([&](const Build& b) { return cost(b) + 1e-2 * b.floor_mm; });
  EXPECT_EQ(calls, 1 + 2 * (kNumBodyRegions - 1 + 2));
  EXPECT_NEAR(shape.build().floor_mm, 45, 1e-3);
  for (int r = 0; r < kNumBodyRegions; ++r) EXPECT_NEAR(shape.build().widths[r], best.widths[r], 1e-3) << r;
  EXPECT_NEAR(shape.build().lengths.legs, 0.93, 1e-3);
  EXPECT_NEAR(shape.build().lengths.arms, 1.06, 1e-3);
  shape.Reset();
  EXPECT_EQ(shape.build(), Build());
}

TEST(BodyShapeTest, NotFiniteCostsAndDisabledLeaveItAlone) {
  BodyShape shape;
  shape.Update([](const Build& b) { return b.lengths.arms > 1.01 ? std::nan("") : 1.0 - b.widths[1]; });
  EXPECT_EQ(shape.build(), Build());
  BodyShapeOptions off;
  off.enabled = false;
  BodyShape disabled(off);
  int calls = 0;
  disabled.Update([&](const Build& b) { return ++calls, b.widths[1]; });
  EXPECT_EQ(calls, 0);
  EXPECT_EQ(disabled.build(), Build());
  // Known lengths: only the widths are fitted.
  BodyShapeOptions widths_only;
  widths_only.lengths = false;
  BodyShape widths(widths_only);
  calls = 0;
  widths.Update([&](const Build& b) { return ++calls, b.lengths.legs + b.widths[3]; });
  EXPECT_EQ(calls, 1 + 2 * (kNumBodyRegions - 1));
  EXPECT_EQ(widths.build().lengths, Proportions());
  EXPECT_LT(widths.build().widths[3], 1);
  BodyShapeOptions bad;
  bad.length_probe = 0;
  std::string why;
  EXPECT_FALSE(bad.Check(&why));
  EXPECT_NE(why.find("probe"), std::string::npos);
}

TEST(BodyShapeTest, FindsTheBuildOfAWalkerFromExactSilhouettes) {
  const Skeleton skeleton = ReadAsf(test::CmuRoot() / "subjects/35/35.asf");
  const Motion motion = ReadAmc(test::CmuRoot() / "subjects/35/35_01.amc", skeleton);
  const Kinematics kinematics(skeleton);
  const Eigen::Matrix3Xd first = kinematics.Compute(motion.Frame(100));
  const Eigen::Vector3d at(first(0, 0), 900, first(2, 0));
  const std::vector<Camera> cameras = {LookAtCamera("side", 320, 240, 330, at + Eigen::Vector3d(4200, 600, 0), at),
                                       LookAtCamera("front", 320, 240, 330, at + Eigen::Vector3d(500, 600, 4200), at)};
  // A broad torso, a small head, thin arms, heavy thighs, thin shins; short legs and long
  // arms. The fit is given the torso's width (the particles' width finds it) and must find
  // the rest relative to it.
  const double torso = 1.15;
  Build truth;
  truth.widths = {1.0, 0.9 / torso, 0.95 / torso, 1.25 / torso, 0.85 / torso};
  truth.lengths = {0.93, 1.06};
  truth.floor_mm = 60;  // the floor higher than the cameras have it
  BodyModelOptions broad;
  broad.width_scale = torso;
  BodyModel walker(skeleton, broad, "35.asf");
  walker.SetRegionScales(truth.widths);
  const BodyModel body(skeleton, {}, "35.asf");
  const LimbScaler limbs(skeleton);
  // The bone ends of frame f with the limbs in proportion (about the hips and shoulders),
  // raised by the floor.
  const auto joints_of = [&](int f, const Build& b) {
    Eigen::Matrix3Xd joints = kinematics.Compute(motion.Frame(f));
    const Eigen::Vector3d root = joints.col(0);
    joints.colwise() -= root;
    double foot = 0;
    limbs.Apply(b.lengths, &joints, &foot);
    joints.colwise() += root + Eigen::Vector3d(0, b.floor_mm, 0);
    return joints;
  };
  const SilhouetteLikelihood likelihood(cameras);
  SilhouetteLikelihood::Workspace workspace = likelihood.NewWorkspace();
  // A walk of 60 frames: each frame's exact masks, the fit on the true pose.
  BodyShape shape;
  std::vector<Capsule> capsules;
  for (int f = 100; f < 160; ++f) {
    std::vector<CameraObservation> observed;
    for (const Camera& camera : cameras) {
      BodyImage image;
      RayCaster(camera).Render(walker.Place(joints_of(f, truth)), &image);
      const cv::Mat mask = image.Mask();
      cv::Rect box = cv::boundingRect(mask);
      observed.push_back(likelihood.Observe(mask, cv::Rect(box.x - 20, box.y - 20, box.width + 40, box.height + 40)));
    }
    shape.Update(
        [&](const Build& b) {
          body.Place(joints_of(f, b), torso, b.widths, &capsules);
          std::vector<CameraScore> scores;
          likelihood.Cost(capsules, observed, &workspace, &scores);
          return ShapeCost(scores);
        },
        true);
  }
  const Build& found = shape.build();
  for (int r = 0; r < kNumBodyRegions; ++r) {
    std::printf("%-7s width  truth %.3f  found %.3f\n", std::string(BodyRegionName(static_cast<BodyRegion>(r))).c_str(),
                truth.widths[r], found.widths[r]);
    EXPECT_NEAR(found.widths[r], truth.widths[r], 0.03) << BodyRegionName(static_cast<BodyRegion>(r));
  }
  std::printf("legs    length truth %.3f  found %.3f\narms    length truth %.3f  found %.3f\n", truth.lengths.legs,
              found.lengths.legs, truth.lengths.arms, found.lengths.arms);
  EXPECT_NEAR(found.lengths.legs, truth.lengths.legs, 0.015);
  EXPECT_NEAR(found.lengths.arms, truth.lengths.arms, 0.02);
  std::printf("floor   truth %.1f mm  found %.1f mm\n", truth.floor_mm, found.floor_mm);
  EXPECT_NEAR(found.floor_mm, truth.floor_mm, 8);
}

}  // namespace
}  // namespace jgpm
