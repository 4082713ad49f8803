// Figures for the tracker's inner loop (issue 13): every particle is a pose drawn as a
// silhouette in every camera and compared with that camera's mask, so these costs, per
// particle and camera, bound the particle count. One benchmark per stage of a particle's
// evaluation, then the filter's resampling and a whole Tracker::Step:
//   pose        the model's pose at a particle's state: exact (GP mean pose + forward
//               kinematics) and tabulated (PoseTable::Lookup + PlaceInWorld, what
//               ManifoldStateModel::Evaluate does for every particle);
//   placement   BodyModel::Place, joints -> capsules;
//   render      BitSilhouetteRenderer::Draw (+ Clear) beside the OpenCV-fill renderer;
//   likelihood  SilhouetteLikelihood::Cost against one camera, and Observe (the per-frame
//               preparation of a camera's mask);
//   resampling  FindBeta + Weights + Resample;
//   frame       Tracker::Step on a 4-camera frame at the default options.
// Counters read directly as time per item (e.g. "10.5us"): `per_particle_camera`,
// `per_particle`, `per_camera_frame`.
//
// Inputs: a synthetic clip of a real walk (07_01, the test subject: 4 cameras of the
// default rig, 320x240, 20 frames at 30 fps, masks by the exact ray caster) rendered into a
// temporary folder at setup; particles are bodies near the truth (neighbouring frames,
// moved by a few cm) or states the prior spreads. The model is $JGPM_MODEL when set, else
// an ML-JGPM torus trained at setup for two L-BFGS iterations: these costs depend on the
// model's size (1800 latent points) and the table's grid, not on how converged it is.
// Everything but the frame runs on one thread (OpenBLAS too).
//
// The first benchmarks (35_01 from 4.5 m, one camera) are the older figures: the
// OpenCV-fill silhouette, body placement and the exact ray caster.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <memory>
#include <random>
#include <string>

#include <opencv2/core/utility.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "io/base/text_reader.h"
#include "io/gait/gait_dataset.h"
#include "io/mocap/amc.h"
#include "io/mocap/asf.h"
#include "io/mocap/kinematics.h"
#include "prior/model/model_file.h"
#include "prior/model/train.h"
#include "prior/numerics/blas_threads.h"
#include "test_support.h"
#include "tracker/body/bit_silhouette.h"
#include "tracker/body/ray_caster.h"
#include "tracker/body/silhouette.h"
#include "tracker/clip/clip_format.h"
#include "tracker/clip/synthetic_clip.h"
#include "tracker/filter/annealed_filter.h"
#include "tracker/filter/likelihood.h"
#include "tracker/filter/tracker.h"
#include "tracker/frames/clip_source.h"
#include "tracker/frames/floor_reflection.h"
#include "tracker/frames/foreground.h"
#include "tracker/run/track_job.h"
#include "tracker/state/manifold_state.h"
#include "tracker/state/pose_table.h"

namespace jgpm {
namespace {

// ---------------------------------------------------------------------------------------
// The older figures: 35_01 seen from the side.

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

// ---------------------------------------------------------------------------------------
// Shared inputs of the per-stage figures.

constexpr int kClipFrames = 20;
constexpr int kCameras = 4;

// Seconds per item (CPU time / items), printed with its SI prefix ("10.5us").
benchmark::Counter TimePer(double items) {
  return benchmark::Counter(items, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

// The model: $JGPM_MODEL, else a quickly trained ML-JGPM torus (see the top of the file).
const GaitModel& Model() {
  static const std::unique_ptr<GaitModel> model = []() -> std::unique_ptr<GaitModel> {
    if (const char* path = std::getenv("JGPM_MODEL"); path && *path) return ReadModelFile(path);
    const GaitDataset dataset =
        PrepareGaitDataset(test::CmuRoot(), "train", test::SplitTrials("train"), GaitCycleOptions{});
    TrainingOptions options;
    options.kind = ModelKind::kMljgpmTorus;
    options.learning = Learning::kFull;
    options.full.max_iterations = 2;
    options.threads = 2;  // setup only; restored after training
    return TrainGaitModel(dataset, {"35_01", ReadTextFile(test::CmuRoot() / "subjects/35/35.asf", "asf")}, options);
  }();
  // Per-call costs on one core, as the tracker's default (one thread) runs them.
  static const LinearAlgebraThreadScope one_thread(1);
  return *model;
}

// The tracker's table at its default options (built on both cores: setup only).
const PoseTable& Table() {
  static const PoseTable table = [] {
    PoseTableOptions options;
    options.threads = 2;
    return PoseTable(Model(), options);
  }();
  return table;
}

// The synthetic clip, in memory.
struct Clip {
  Skeleton skeleton;                        // 07's
  ClipGroundTruth truth;
  std::vector<Frame> frames;                // observed masks and video images, from ClipFrameSource
  std::vector<cv::Mat> backgrounds;         // per camera: the empty room
  std::vector<std::vector<Capsule>> truth_bodies;  // per frame
  std::vector<std::vector<Capsule>> tracking_bodies;  // the same, as the tracker draws them (BodyDetail::kTracking)
  std::vector<std::vector<cv::Rect>> regions;      // per frame and camera: around the walker
  std::vector<std::unique_ptr<SilhouetteLikelihood>> single;  // one camera each
  // Per frame and camera, that camera's observation alone (Cost takes one per camera of
  // its likelihood).
  std::vector<std::vector<std::vector<CameraObservation>>> observed;
  // Particle-like bodies (ParticleBody) and the frame each is scored against.
  std::vector<std::vector<Capsule>> particle_bodies;
  std::vector<int> particle_frame;
};

// The box of a mask grown as the tracker grows its predicted box (region_margin 0.4).
cv::Rect RegionAround(const cv::Mat& mask) {
  const cv::Rect box = cv::boundingRect(mask);
  const int dx = static_cast<int>(0.4 * box.width) + 8, dy = static_cast<int>(0.4 * box.height) + 8;
  return cv::Rect(box.x - dx, box.y - dy, box.width + 2 * dx, box.height + 2 * dy) & cv::Rect(0, 0, mask.cols, mask.rows);
}

// A body as a particle near the truth of frame `f` has it: the pose of a frame up to 2
// away (the phase a little off), moved on the floor by ~40 mm.
std::vector<Capsule> ParticleBody(const Clip& clip, const BodyModel& body, int f, std::mt19937* random) {
  std::normal_distribution<double> move(0, 40);
  std::uniform_int_distribution<int> phase(-2, 2);
  const int frames = static_cast<int>(clip.truth.frames.size());
  Eigen::Matrix3Xd joints = clip.truth.frames[std::clamp(f + phase(*random), 0, frames - 1)].joints_mm;
  joints.colwise() += Eigen::Vector3d(move(*random), 0, move(*random));
  return body.Place(joints);
}

const Clip& TheClip() {
  static const Clip clip = [] {
    Clip k;
    const std::filesystem::path asf = test::CmuRoot() / "subjects/07/07.asf";
    const std::filesystem::path amc = test::CmuRoot() / "subjects/07/07_01.amc";
    k.skeleton = ReadAsf(asf);
    const Motion motion = ReadAmc(amc, k.skeleton);
    ClipOptions options;
    options.max_frames = kClipFrames;
    options.rig.num_cameras = kCameras;
    options.rig.width = 320;
    options.rig.height = 240;
    options.contact_sheet = false;
    {
      const test::TempDir dir;  // the clip lives only while it is read
      const std::filesystem::path folder = dir.path() / "clip";
      RenderClip(k.skeleton, motion, {asf.string(), amc.string()}, {}, options, folder.string());
      ClipFrameSourceOptions source_options;
      source_options.with_images = true;
      ClipFrameSource source(folder, source_options);
      k.truth = source.truth();
      for (const Camera& camera : k.truth.cameras)
        k.backgrounds.push_back(cv::imread(ClipPaths{folder}.Background(camera.name).string(), cv::IMREAD_COLOR));
      Frame frame;
      while (source.Next(&frame)) k.frames.push_back(frame);
    }
    const BodyModel body(k.skeleton, {}, "07.asf");
    const BodyModel tracking_body(k.skeleton, {.detail = BodyDetail::kTracking}, "07.asf");
    for (const ClipFrame& f : k.truth.frames) {
      k.truth_bodies.push_back(body.Place(f.joints_mm));
      k.tracking_bodies.push_back(tracking_body.Place(f.joints_mm));
    }
    for (const Camera& camera : k.truth.cameras)
      k.single.push_back(std::make_unique<SilhouetteLikelihood>(std::vector<Camera>{camera}));
    for (const Frame& f : k.frames) {
      k.regions.emplace_back();
      k.observed.emplace_back();
      for (int c = 0; c < kCameras; ++c) {
        k.regions.back().push_back(RegionAround(f.masks[c]));
        k.observed.back().push_back({k.single[c]->Observe(f.masks[c], k.regions.back().back())});
      }
    }
    std::mt19937 random(7);
    for (int i = 0; i < 256; ++i) {
      const int f = i % static_cast<int>(k.truth.frames.size());
      k.particle_bodies.push_back(ParticleBody(k, body, f, &random));
      k.particle_frame.push_back(f);
    }
    return k;
  }();
  return clip;
}

// Particle states of the model spread by the prior about the walker's first place (any
// pose, phase, gait and scale; heading and size near the truth), as a start spreads them.
struct Particles {
  std::unique_ptr<ManifoldStateModel> model;
  std::vector<Eigen::VectorXd> states;
};

const Particles& TheParticles() {
  static const Particles particles = [] {
    Particles p;
    p.model = std::make_unique<ManifoldStateModel>(Model(), Table());
    const Eigen::Matrix3Xd& root = TheClip().truth.frames[0].joints_mm;
    InitialGuess guess;
    guess.floor_mm = Eigen::Vector2d(root(0, 0), root(2, 0));
    guess.heading_std_rad = 0.4;
    for (int i = 0; i < 256; ++i) {
      Random random(99, 0, 0, i);
      Eigen::VectorXd s(p.model->Dimension());
      p.model->Sample(guess, &random, s.data());
      p.states.push_back(s);
    }
    return p;
  }();
  return particles;
}

// ---------------------------------------------------------------------------------------
// Pose: the model's bone ends in the world at a particle's state.

// (a) Exact: the manifold point's latent point, the GP mean pose there (MeanPoses of one
// point, O(N D)), forward kinematics and placement (PosePlacer::Place). What the tracker
// does once per frame for its estimate (Tracker::Exact) and the refiner per candidate.
void BM_PoseExact(benchmark::State& state) {
  const GaitModel& model = Model();
  const Particles& particles = TheParticles();
  const PosePlacer placer(model.skeleton());
  ModelWorkspace workspace;
  Eigen::MatrixXd xs(1, 3), pose(1, model.NumChannels());
  Eigen::Matrix3Xd world;
  size_t i = 0;
  for (auto _ : state) {
    const Eigen::VectorXd& s = particles.states[i++ % particles.states.size()];
    xs.row(0) = model.ManifoldToLatent({s[0], s[1], s[2]}).transpose();
    model.MeanPoses(xs, pose, &workspace);
    placer.Place(pose.data(), s[3], s[4], s[5], s[7], &world);
    benchmark::DoNotOptimize(world.data());
  }
  state.counters["latent_points"] = model.NumPoints();
  state.counters["per_particle"] = TimePer(static_cast<double>(state.iterations()));
}
BENCHMARK(BM_PoseExact)->Unit(benchmark::kMicrosecond);

// (b) Tabulated: trilinear lookup in the pose table and placement in the world (what
// ManifoldStateModel::Evaluate does for every particle and layer).
void BM_PoseTable(benchmark::State& state) {
  const PoseTable& table = Table();
  const Particles& particles = TheParticles();
  Eigen::Matrix3Xd relative, world;
  double foot = 0, log_density = 0;
  size_t i = 0;
  for (auto _ : state) {
    const Eigen::VectorXd& s = particles.states[i++ % particles.states.size()];
    table.Lookup(Eigen::Vector3d(s[0], s[1], s[2]), &relative, &foot, &log_density);
    PlaceInWorld(relative, foot, s[3], s[4], s[5], s[7], kFootClearanceMm, &world);
    benchmark::DoNotOptimize(world.data());
    benchmark::DoNotOptimize(log_density);
  }
  state.counters["per_particle"] = TimePer(static_cast<double>(state.iterations()));
}
BENCHMARK(BM_PoseTable);

// ---------------------------------------------------------------------------------------
// Placement: joints -> capsules on the clip's walker (BM_PlaceBody above is the same on
// 35_01); the filter then scales each radius by the particle's size.

void BM_PlaceBodyWalker(benchmark::State& state) {
  const Clip& clip = TheClip();
  const BodyModel body(clip.skeleton, {}, "07.asf");
  std::vector<Capsule> capsules;
  size_t i = 0;
  for (auto _ : state) {
    body.Place(clip.truth.frames[i++ % clip.truth.frames.size()].joints_mm, &capsules);
    for (Capsule& c : capsules) c.radius_from_mm *= 1.01, c.radius_to_mm *= 1.01;
    benchmark::DoNotOptimize(capsules.data());
  }
  state.counters["per_particle"] = TimePer(static_cast<double>(state.iterations()));
}
BENCHMARK(BM_PlaceBodyWalker);

// ---------------------------------------------------------------------------------------
// Render: one body in one camera (cameras and frames taken in turn), 320x240. First
// argument 0: the mask only; 1: with the outline points the likelihood asks for (every 3
// px). Second: 0 every part of the body model (30), 1 the tracker's 25 (BodyDetail).

void BM_RenderBits(benchmark::State& state) {
  const Clip& clip = TheClip();
  const bool outline = state.range(0) != 0;
  const auto& bodies = state.range(1) ? clip.tracking_bodies : clip.truth_bodies;
  std::vector<BitSilhouetteRenderer> renderers;
  std::vector<BitMask> masks;
  for (const Camera& camera : clip.truth.cameras) {
    renderers.emplace_back(camera);
    masks.emplace_back(camera.width, camera.height);
  }
  std::vector<Eigen::Vector2f> points;
  points.reserve(2048);
  size_t i = 0, n = 0;
  for (auto _ : state) {
    const int c = static_cast<int>(i % kCameras);
    points.clear();
    renderers[c].Draw(bodies[(i / kCameras) % bodies.size()], &masks[c],
                      outline ? &points : nullptr);
    benchmark::DoNotOptimize(masks[c].row(0));
    n += points.size();
    masks[c].Clear();
    ++i;
  }
  state.SetLabel(std::string(outline ? "bit spans + outline" : "bit spans") + (state.range(1) ? ", tracking body" : ", full body"));
  state.counters["outline_points"] = static_cast<double>(n) / std::max<double>(1, i);
  state.counters["per_particle_camera"] = TimePer(static_cast<double>(state.iterations()));
}
BENCHMARK(BM_RenderBits)->Args({0, 0})->Args({1, 0})->Args({0, 1})->Args({1, 1});

// The OpenCV-fill renderer in the particle filter's form: Draw into a kept-blank mask,
// then blank what was drawn.
void BM_RenderOpenCv(benchmark::State& state) {
  const Clip& clip = TheClip();
  const bool outline = state.range(0) != 0;
  std::vector<SilhouetteRenderer> renderers;
  std::vector<cv::Mat> masks;
  for (const Camera& camera : clip.truth.cameras) {
    renderers.emplace_back(camera);
    masks.push_back(cv::Mat::zeros(camera.height, camera.width, CV_8UC1));
  }
  std::vector<Eigen::Vector2f> points;
  points.reserve(2048);
  size_t i = 0;
  for (auto _ : state) {
    const int c = static_cast<int>(i % kCameras);
    points.clear();
    const cv::Rect box = renderers[c].Draw(clip.truth_bodies[(i / kCameras) % clip.truth_bodies.size()], &masks[c],
                                           outline ? &points : nullptr);
    benchmark::DoNotOptimize(masks[c].data);
    masks[c](box).setTo(0);
    ++i;
  }
  state.SetLabel(outline ? "opencv fill + outline" : "opencv fill");
  state.counters["per_particle_camera"] = TimePer(static_cast<double>(state.iterations()));
}
BENCHMARK(BM_RenderOpenCv)->Arg(0)->Arg(1);

// ---------------------------------------------------------------------------------------
// Likelihood.

// One body's cost against one camera's observation (draw with outline, counts, outline
// distances, clear): particle-like bodies near the truth, cameras in turn. Arg 0: every
// body against frame 10's observations, as the filter scores all its particles against
// one frame (4 cameras' distance maps, 1.2 MB, stay in the caches); 1: each body against
// its own frame of the 20 (~25 MB of distance maps do not: a cold-cache bound).
void BM_LikelihoodCost(benchmark::State& state) {
  const Clip& clip = TheClip();
  const bool one_frame = state.range(0) == 0;
  std::vector<SilhouetteLikelihood::Workspace> workspaces;
  for (const auto& l : clip.single) workspaces.push_back(l->NewWorkspace());
  std::vector<std::vector<Capsule>> bodies;
  if (one_frame) {
    const BodyModel body(clip.skeleton, {}, "07.asf");
    std::mt19937 random(3);
    for (int i = 0; i < 256; ++i) bodies.push_back(ParticleBody(clip, body, 10, &random));
  }
  size_t i = 0;
  double sum = 0;
  for (auto _ : state) {
    const int c = static_cast<int>(i % kCameras);
    const size_t p = (i / kCameras) % clip.particle_bodies.size();
    sum += one_frame ? clip.single[c]->Cost(bodies[p], clip.observed[10][c], &workspaces[c])
                     : clip.single[c]->Cost(clip.particle_bodies[p], clip.observed[clip.particle_frame[p]][c],
                                            &workspaces[c]);
    ++i;
  }
  benchmark::DoNotOptimize(sum);
  state.SetLabel(one_frame ? "one frame" : "20 frames in turn");
  state.counters["mean_cost"] = sum / std::max<double>(1, i);
  state.counters["per_particle_camera"] = TimePer(static_cast<double>(state.iterations()));
}
BENCHMARK(BM_LikelihoodCost)->Arg(0)->Arg(1);

// A camera's mask prepared for a frame (hole filling, distance transform, integral image,
// the region's foreground packed and grown): once per camera and frame. OpenCV on one
// thread (its connected components and distance transform can use its worker threads,
// whose time the benchmark's CPU time would not see).
void BM_LikelihoodObserve(benchmark::State& state) {
  const Clip& clip = TheClip();
  const int threads = cv::getNumThreads();
  cv::setNumThreads(1);
  size_t i = 0;
  for (auto _ : state) {
    const int c = static_cast<int>(i % kCameras);
    const size_t f = (i / kCameras) % clip.frames.size();
    CameraObservation o = clip.single[c]->Observe(clip.frames[f].masks[c], clip.regions[f][c]);
    benchmark::DoNotOptimize(o.region_count());
    ++i;
  }
  cv::setNumThreads(threads);
  state.counters["per_camera_frame"] = TimePer(static_cast<double>(state.iterations()));
}
BENCHMARK(BM_LikelihoodObserve)->Unit(benchmark::kMicrosecond);

// The floor-reflection cut tried on one camera's observed mask (tracker/frames/
// floor_reflection.h): every frame of every camera pays it, glossy floor or not, to gather
// the evidence. OpenCV on one thread, as above.
void BM_CutFloorReflections(benchmark::State& state) {
  const Clip& clip = TheClip();
  const int threads = cv::getNumThreads();
  cv::setNumThreads(1);
  size_t i = 0;
  for (auto _ : state) {
    const int c = static_cast<int>(i % kCameras);
    const size_t f = (i / kCameras) % clip.frames.size();
    cv::Mat mask = clip.frames[f].masks[c];
    benchmark::DoNotOptimize(CutFloorReflections(clip.truth.cameras[c], &mask).tried);
    ++i;
  }
  cv::setNumThreads(threads);
  state.counters["per_camera_frame"] = TimePer(static_cast<double>(state.iterations()));
}
BENCHMARK(BM_CutFloorReflections)->Unit(benchmark::kMicrosecond);

// A colour frame to a mask by background subtraction (tracker/frames/foreground.h), as for a
// recording: gain compensation, MOG2 (0) or KNN (1), clean-up, specks. OpenCV on one
// thread, as above.
void BM_Foreground(benchmark::State& state) {
  const Clip& clip = TheClip();
  const int threads = cv::getNumThreads();
  cv::setNumThreads(1);
  ForegroundOptions options;
  options.method = state.range(0) ? ForegroundMethod::kKnn : ForegroundMethod::kMog2;
  std::vector<ForegroundExtractor> extractors;
  for (int c = 0; c < kCameras; ++c) {
    extractors.emplace_back(options, clip.truth.cameras[c].width, clip.truth.cameras[c].height);
    extractors.back().SetBackground(clip.backgrounds[c]);
  }
  size_t i = 0;
  for (auto _ : state) {
    const int c = static_cast<int>(i % kCameras);
    const size_t f = (i / kCameras) % clip.frames.size();
    benchmark::DoNotOptimize(extractors[c].Apply(clip.frames[f].images[c]).data);
    ++i;
  }
  cv::setNumThreads(threads);
  state.counters["per_camera_frame"] = TimePer(static_cast<double>(state.iterations()));
}
BENCHMARK(BM_Foreground)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);

// ---------------------------------------------------------------------------------------
// Resampling: one annealing layer's bookkeeping for N particles: beta by bisection on the
// effective sample size, the weights, systematic resampling. Costs are real: N bodies near
// the truth scored in all 4 cameras of frame 10; ln p(x|M) from the table at prior-spread
// states.

void BM_Resampling(benchmark::State& state) {
  const Clip& clip = TheClip();
  const Particles& particles = TheParticles();
  const int n = static_cast<int>(state.range(0));
  std::vector<double> cost(n), log_prior(n);
  {
    const int f = 10;
    std::vector<CameraObservation> all;
    for (int c = 0; c < kCameras; ++c) all.push_back(clip.observed[f][c][0]);
    const SilhouetteLikelihood likelihood(clip.truth.cameras);
    SilhouetteLikelihood::Workspace workspace = likelihood.NewWorkspace();
    const BodyModel body(clip.skeleton, {}, "07.asf");
    std::mt19937 random(11);
    Eigen::Matrix3Xd joints;
    for (int i = 0; i < n; ++i) {
      cost[i] = likelihood.Cost(ParticleBody(clip, body, f, &random), all, &workspace);
      log_prior[i] = particles.model->Evaluate(particles.states[i % particles.states.size()].data(), &joints);
    }
  }
  double beta = 0;
  for (auto _ : state) {
    beta = AnnealedFilter::FindBeta(cost, log_prior, 0.5);
    const std::vector<double> weights = AnnealedFilter::Weights(cost, log_prior, beta);
    const std::vector<int> chosen = AnnealedFilter::Resample(weights, n, 0.37);
    benchmark::DoNotOptimize(chosen.data());
  }
  state.counters["beta"] = beta;
  state.counters["per_particle"] = TimePer(static_cast<double>(state.iterations()) * n);
}
BENCHMARK(BM_Resampling)->Arg(200)->Arg(1000)->Unit(benchmark::kMicrosecond);

// ---------------------------------------------------------------------------------------
// A whole frame: Tracker::Step on the clip's 4-camera frames at the default options (200
// particles, 4 layers, pose refinement, one thread), after the start frame. Arg 0: started
// from the masks of the first 15 frames (as `jgpm track` starts); 1: from the clip's truth
// (`--init truth`). Frames 1..19 in turn; after the last, the tracker starts again (not
// timed). CPU time is the process's (OpenCV's worker threads included).
// `per_particle_camera` is the frame's time over its likelihood evaluations times
// cameras: everything a frame costs, charged to the particles.

void StartTracker(const Clip& clip, bool from_truth, Tracker* tracker) {
  if (from_truth) {
    tracker->StartAt(TruthGuess(clip.truth, Model(), tracker->state_model()));
  } else {
    tracker->StartFromFrames(std::vector<Frame>(clip.frames.begin(), clip.frames.begin() + 15));
  }
  tracker->Step(clip.frames[0]);  // the start frame: more particles and layers
}

void BM_TrackerStep(benchmark::State& state) {
  const Clip& clip = TheClip();
  const bool from_truth = state.range(0) != 0;
  Tracker tracker(Model(), clip.truth.cameras, TrackerOptions{});
  StartTracker(clip, from_truth, &tracker);
  size_t next = 1;
  double evaluations = 0, iou = 0, lost = 0;
  for (auto _ : state) {
    if (next == clip.frames.size()) {
      state.PauseTiming();
      StartTracker(clip, from_truth, &tracker);
      next = 1;
      state.ResumeTiming();
    }
    const TrackedFrame out = tracker.Step(clip.frames[next++]);
    evaluations += out.evaluations;
    iou += out.MeanIou();
    lost += out.status == TrackStatus::kLost;
  }
  const double frames = static_cast<double>(state.iterations());
  state.SetLabel(from_truth ? "start: truth" : "start: masks");
  state.counters["frames_per_s"] = benchmark::Counter(frames, benchmark::Counter::kIsRate);
  state.counters["evals_per_frame"] = evaluations / frames;
  state.counters["mean_iou"] = iou / frames;
  state.counters["lost"] = lost;
  state.counters["per_particle_camera"] = TimePer(evaluations * kCameras);
}
BENCHMARK(BM_TrackerStep)
    ->Arg(0)
    ->Arg(1)
    ->Iterations(2 * (kClipFrames - 1))
    ->MeasureProcessCPUTime()
    ->Unit(benchmark::kMillisecond);

// The start frame alone (start_particle_factor 4 x 200 particles, 8 layers), from truth.
void BM_TrackerStartFrame(benchmark::State& state) {
  const Clip& clip = TheClip();
  Tracker tracker(Model(), clip.truth.cameras, TrackerOptions{});
  double evaluations = 0;
  for (auto _ : state) {
    state.PauseTiming();
    tracker.StartAt(TruthGuess(clip.truth, Model(), tracker.state_model()));
    state.ResumeTiming();
    evaluations += tracker.Step(clip.frames[0]).evaluations;
  }
  state.counters["evals_per_frame"] = evaluations / static_cast<double>(state.iterations());
  state.counters["per_particle_camera"] = TimePer(evaluations * kCameras);
}
BENCHMARK(BM_TrackerStartFrame)->Iterations(3)->MeasureProcessCPUTime()->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace jgpm

BENCHMARK_MAIN();
