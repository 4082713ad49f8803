// Figures for the tracker's inner loop: every particle is a pose drawn as a silhouette in
// every camera, so the silhouette's cost per image bounds the particle count. Poses are
// the frames of a real walk (35_01) seen at 320x240 from 4.5 m; the exact ray caster (what
// the synthetic clips' ground truth uses) is measured beside the fast renderer.
#include <benchmark/benchmark.h>

#include <cmath>

#include <opencv2/core/utility.hpp>

#include "io/amc.h"
#include "io/asf.h"
#include "io/kinematics.h"
#include "test_support.h"
#include "tracker/ray_caster.h"
#include "tracker/silhouette.h"

namespace jgpm {
namespace {

struct Scene {
  Skeleton skeleton;
  std::vector<std::vector<Capsule>> poses;  // one per frame, placed
  std::vector<Eigen::Matrix3Xd> joints;
  Camera camera;
};

const Scene& TheScene() {
  static const Scene scene = [] {
    Scene s;
    s.skeleton = ReadAsf(test::CmuRoot() / "subjects/35/35.asf");
    const Motion motion = ReadAmc(test::CmuRoot() / "subjects/35/35_01.amc", s.skeleton);
    const BodyModel body(s.skeleton, {}, "35.asf");
    s.joints = ComputeJointPositions(s.skeleton, motion);
    for (const Eigen::Matrix3Xd& j : s.joints) s.poses.push_back(body.Place(j));
    const Eigen::Vector3d mid = 0.5 * (s.joints.front().col(0) + s.joints.back().col(0));
    s.camera = LookAtCamera("side", 320, 240, 280, {mid.x() + 4500, 1500, mid.z()}, {mid.x(), 900, mid.z()});
    s.camera.distortion = {-0.1, 0.02, 0, 0, 0};
    return s;
  }();
  return scene;
}

void BM_Silhouette320x240(benchmark::State& state) {
  const Scene& scene = TheScene();
  const SilhouetteRenderer renderer(scene.camera);
  cv::Mat mask;
  size_t i = 0;
  for (auto _ : state) {
    renderer.Render(scene.poses[i++ % scene.poses.size()], &mask);
    benchmark::DoNotOptimize(mask.data);
  }
  state.counters["parts"] = static_cast<double>(scene.poses[0].size());
}
BENCHMARK(BM_Silhouette320x240);

// Placing the body at a pose's joints (the step between kinematics and drawing).
void BM_PlaceBody(benchmark::State& state) {
  const Scene& scene = TheScene();
  const BodyModel body(scene.skeleton, {}, "35.asf");
  std::vector<Capsule> capsules;
  size_t i = 0;
  for (auto _ : state) {
    body.Place(scene.joints[i++ % scene.joints.size()], &capsules);
    benchmark::DoNotOptimize(capsules.data());
  }
}
BENCHMARK(BM_PlaceBody);

// The exact renderer, one thread (it runs rows in parallel when allowed).
void BM_RayCast320x240(benchmark::State& state) {
  const Scene& scene = TheScene();
  const int threads = cv::getNumThreads();
  cv::setNumThreads(1);
  const RayCaster caster(scene.camera);
  BodyImage image;
  size_t i = 0;
  for (auto _ : state) {
    caster.Render(scene.poses[(i += 7) % scene.poses.size()], &image);
    benchmark::DoNotOptimize(image.part.data);
  }
  cv::setNumThreads(threads);
}
BENCHMARK(BM_RayCast320x240)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace jgpm

BENCHMARK_MAIN();
