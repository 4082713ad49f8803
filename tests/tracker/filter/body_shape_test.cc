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
#include "tracker/clip/clip_body.h"
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
  EXPECT_EQ(calls, 1 + 2 * (kNumBodyRegions - 1 + 2 + 1 + 1));
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
  EXPECT_EQ(calls, 1 + 2 * (kNumBodyRegions - 1 + 2 + 1));
  EXPECT_NEAR(shape.build().floor_mm, 45, 1e-3);
  EXPECT_EQ(shape.build().garment, 0);  // the cost does not ask for one
  for (int r = 0; r < kNumBodyRegions; ++r) EXPECT_NEAR(shape.build().widths[r], best.widths[r], 1e-3) << r;
  EXPECT_NEAR(shape.build().lengths.legs, 0.93, 1e-3);
  EXPECT_NEAR(shape.build().lengths.arms, 1.06, 1e-3);
  shape.Reset();
  EXPECT_EQ(shape.build(), Build());
}

// The garment goes to a quadratic's minimum from 0 (a probe below 0 draws none: the cost
// there is the cost at 0), and is drawn only from garment_drawn on.
TEST(BodyShapeTest, TheGarmentIsLearntFromNoneAndDrawnOnceItIsWiderThanTheLegs) {
  for (const double best : {0.3, 0.9}) {
    BodyShape shape;
    for (int i = 0; i < 100; ++i) shape.Update([&](const Build& b) { return std::pow(std::max(b.garment, 0.0) - best, 2); });
    EXPECT_NEAR(shape.build().garment, best, 1e-3);
    EXPECT_EQ(shape.drawn().garment, best < BodyShapeOptions().garment_drawn ? 0 : shape.build().garment);
    Build rest = shape.drawn();
    rest.garment = shape.build().garment;
    EXPECT_EQ(rest, shape.build());  // nothing else differs
  }
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
  widths_only.garment = false;
  BodyShape widths(widths_only);
  calls = 0;
  widths.Update([&](const Build& b) { return ++calls, b.lengths.legs + b.widths[3] - b.garment; });
  EXPECT_EQ(calls, 1 + 2 * (kNumBodyRegions - 1));
  EXPECT_EQ(widths.build().garment, 0);
  EXPECT_EQ(widths.build().lengths, Proportions());
  EXPECT_LT(widths.build().widths[3], 1);
  BodyShapeOptions bad;
  bad.length_probe = 0;
  std::string why;
  EXPECT_FALSE(bad.Check(&why));
  EXPECT_NE(why.find("probe"), std::string::npos);
}

// Subject 35's walk seen from the side and the front, 4.2 m away.
struct SideAndFront {
  Skeleton skeleton = ReadAsf(test::CmuRoot() / "subjects/35/35.asf");
  Motion motion = ReadAmc(test::CmuRoot() / "subjects/35/35_01.amc", skeleton);
  Kinematics kinematics{skeleton};
  std::vector<Camera> cameras;
  SideAndFront() {
    const Eigen::Matrix3Xd first = kinematics.Compute(motion.Frame(100));
    const Eigen::Vector3d at(first(0, 0), 900, first(2, 0));
    cameras = {LookAtCamera("side", 320, 240, 330, at + Eigen::Vector3d(4200, 600, 0), at),
               LookAtCamera("front", 320, 240, 330, at + Eigen::Vector3d(500, 600, 4200), at)};
  }
  // The exact masks of `shapes` (ray cast), each observed in a box 20 px about the person.
  std::vector<CameraObservation> Observe(const SilhouetteLikelihood& likelihood, const std::vector<Capsule>& shapes) const {
    std::vector<CameraObservation> observed;
    for (const Camera& camera : cameras) {
      BodyImage image;
      RayCaster(camera).Render(shapes, &image);
      const cv::Mat mask = image.Mask();
      const cv::Rect box = cv::boundingRect(mask);
      observed.push_back(likelihood.Observe(mask, cv::Rect(box.x - 20, box.y - 20, box.width + 40, box.height + 40)));
    }
    return observed;
  }
};

TEST(BodyShapeTest, FindsTheBuildOfAWalkerFromExactSilhouettes) {
  const SideAndFront scene;
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
  BodyModel walker(scene.skeleton, broad, "35.asf");
  walker.SetRegionScales(truth.widths);
  const BodyModel body(scene.skeleton, {}, "35.asf");
  const LimbScaler limbs(scene.skeleton);
  // The bone ends of frame f with the limbs in proportion (about the hips and shoulders),
  // raised by the floor.
  const auto joints_of = [&](int f, const Build& b) {
    Eigen::Matrix3Xd joints = scene.kinematics.Compute(scene.motion.Frame(f));
    const Eigen::Vector3d root = joints.col(0);
    joints.colwise() -= root;
    double foot = 0;
    limbs.Apply(b.lengths, &joints, &foot);
    joints.colwise() += root + Eigen::Vector3d(0, b.floor_mm, 0);
    return joints;
  };
  const SilhouetteLikelihood likelihood(scene.cameras);
  SilhouetteLikelihood::Workspace workspace = likelihood.NewWorkspace();
  // A walk of 60 frames: each frame's exact masks, the fit on the true pose.
  BodyShape shape;
  std::vector<Capsule> capsules;
  for (int f = 100; f < 160; ++f) {
    const std::vector<CameraObservation> observed = scene.Observe(likelihood, walker.Place(joints_of(f, truth)));
    shape.Update(
        [&](const Build& b) {
          body.Place(joints_of(f, b), torso, b.widths, b.garment, &capsules);
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
  // A bare walker: the cloth between the thighs is not there to explain.
  std::printf("garment truth 0  found %.3f\n", found.garment);
  EXPECT_LT(found.garment, 0.15);
}

// A walker in a skirt (the clips' cone, tracker/clip/clip_body.h, a shape the garment only
// approximates). Without a garment the cloth between the thighs pulls the thighs' and
// shins' widths up; with it the garment grows to about the skirt's hem, the shins stay
// near their width, and the true pose is explained better than by the bare fit.
TEST(BodyShapeTest, ASkirtIsLearntAsAGarmentNotAsFatLegs) {
  const SideAndFront scene;
  ClipBodyOptions skirt;
  skirt.clothing = Clothing::kSkirt;
  const ClipBody walker(scene.skeleton, skirt, "35.asf");
  const BodyModel body(scene.skeleton, {}, "35.asf");
  const SilhouetteLikelihood likelihood(scene.cameras);
  SilhouetteLikelihood::Workspace workspace = likelihood.NewWorkspace();
  std::vector<std::vector<CameraObservation>> frames;
  for (int f = 100; f < 160; ++f) {
    std::vector<Capsule> shapes;
    walker.Place(scene.kinematics.Compute(scene.motion.Frame(f)), &shapes);
    frames.push_back(scene.Observe(likelihood, shapes));
  }
  std::vector<Capsule> capsules;
  const auto cost = [&](int k, const Build& b) {
    body.Place(scene.kinematics.Compute(scene.motion.Frame(100 + k)), 1.0, b.widths, b.garment, &capsules);
    std::vector<CameraScore> scores;
    likelihood.Cost(capsules, frames[k], &workspace, &scores);
    return ShapeCost(scores);
  };
  const auto fit = [&](bool garment) {
    BodyShapeOptions options;
    options.lengths = false;
    options.garment = garment;
    BodyShape shape(options);
    for (int k = 0; k < static_cast<int>(frames.size()); ++k)
      shape.Update([&](const Build& b) { return cost(k, b); }, true);
    double mean = 0;  // the last ten frames' cost with the build found
    for (int k = 50; k < 60; ++k) mean += cost(k, shape.build()) / 10;
    return std::make_pair(shape.build(), mean);
  };
  const auto [bare, bare_cost] = fit(false);
  const auto [dressed, dressed_cost] = fit(true);
  const int shins = static_cast<int>(BodyRegion::kShins), thighs = static_cast<int>(BodyRegion::kThighs);
  std::printf("bare:    thighs %.2f shins %.2f cost %.3f\ndressed: thighs %.2f shins %.2f garment %.2f cost %.3f\n",
              bare.widths[thighs], bare.widths[shins], bare_cost, dressed.widths[thighs], dressed.widths[shins],
              dressed.garment, dressed_cost);
  // The skirt's hem (245 mm at 85% of the way to the knees) against the garment's
  // (kGarmentHemMm at kGarmentLength): within a quarter.
  const double hem_at_garment_length = 150 + (245 - 150) * kGarmentLength / 0.85;
  EXPECT_NEAR(dressed.garment * kGarmentHemMm, hem_at_garment_length, 0.25 * hem_at_garment_length);
  EXPECT_LT(dressed.widths[shins], 1.1);
  EXPECT_GT(bare.widths[thighs], dressed.widths[thighs]);
  EXPECT_LT(dressed_cost, 0.8 * bare_cost);
}

}  // namespace
}  // namespace jgpm
