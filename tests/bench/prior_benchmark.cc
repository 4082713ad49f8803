// Figures for the prior layer: the tracker evaluates the mean pose plus forward kinematics
// (and log p(x|M)) for every particle, so their cost per latent point matters. The model
// is an ML-JGPM (1800 latent points) on the default training split; its quality does not
// change these costs, so it is trained for a few iterations only.
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <cmath>
#include <random>

#include "io/base/heap.h"
#include "io/base/text_reader.h"
#include "io/gait/data_root.h"
#include "io/gait/gait_dataset.h"
#include "prior/eval/learning_scaling.h"
#include "prior/learning/objective.h"
#include "prior/model/inference.h"
#include "prior/model/model_file.h"
#include "prior/model/train.h"
#include "prior/numerics/blas_threads.h"
#include "prior/numerics/rbf_row.h"
#include "test_support.h"

namespace jgpm {
namespace {

// As the jgpm command does, so that the figures are the ones it gets.
const bool kFreedMemoryKept = KeepFreedMemory();

// $JGPM_MODEL (a model file, e.g. the quick start's) when set: the inference figures
// depend on how far the solver goes, which a 2-iteration model does not show.
const GaitModel& Model() {
  static const std::unique_ptr<GaitModel> model = []() -> std::unique_ptr<GaitModel> {
    static const LinearAlgebraThreadScope one_thread(1);  // per-call costs on one core
    if (const char* path = std::getenv("JGPM_MODEL")) return ReadModelFile(path);
    const GaitDataset dataset =
        PrepareGaitDataset(test::CmuRoot(), "train", test::SplitTrials("train"), GaitCycleOptions{});
    TrainingOptions options;
    options.kind = ModelKind::kMljgpmTorus;
    options.full.max_iterations = 2;
    options.threads = 1;
    return TrainGaitModel(dataset, {"35_01", ReadTextFile(test::CmuRoot() / "subjects/35/35.asf", "asf")}, options);
  }();
  return *model;
}

std::vector<Eigen::Vector3d> Queries(const GaitModel& model) {
  std::mt19937 random(1);
  std::normal_distribution<double> noise(0, 0.1);
  std::vector<Eigen::Vector3d> queries;
  for (int i = 0; i < 256; ++i) {
    queries.push_back(model.latent().row((i * 37) % model.NumPoints()).transpose() +
                      Eigen::Vector3d(noise(random), noise(random), noise(random)));
  }
  return queries;
}

// One kernel row against all 1800 latent points, the inner loop of prediction: the
// vectorised RbfRow side by side with the plain Eigen expression it replaced.
void BM_KernelRow(benchmark::State& state) {
  const GaitModel& model = Model();
  const Eigen::MatrixXd& x = model.latent();
  const auto queries = Queries(model);
  Eigen::VectorXd k(x.rows());
  size_t i = 0;
  for (auto _ : state) {
    const Eigen::Vector3d& q = queries[i++ % queries.size()];
    if (state.range(0) == 0) {
      k = 1.5 * (-0.5 * (x.rowwise() - q.transpose()).rowwise().squaredNorm().array()).exp().matrix();
    } else {
      RbfRow(x.data(), static_cast<int>(x.rows()), q.data(), 1.5, 1.0, k.data());
    }
    benchmark::DoNotOptimize(k.data());
  }
  state.SetLabel(state.range(0) == 0 ? "eigen" : "rbf_row");
}
BENCHMARK(BM_KernelRow)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);

void BM_MeanPoseAndKinematics(benchmark::State& state) {
  const GaitModel& model = Model();
  const auto queries = Queries(model);
  Eigen::VectorXd pose;
  Eigen::Matrix3Xd joints;
  size_t i = 0;
  for (auto _ : state) {
    model.Predict(queries[i++ % queries.size()], &pose, nullptr);
    model.JointPositions(pose, &joints);
    benchmark::DoNotOptimize(joints.data());
  }
  state.counters["latent_points"] = model.NumPoints();
}
BENCHMARK(BM_MeanPoseAndKinematics)->Unit(benchmark::kMicrosecond);

// Mean poses of a batch of 1000 latent points (the batch call `import jgpm`'s
// Model.mean_pose makes): the per-point figure the Python binding's overhead is measured
// against (README, Python).
void BM_MeanPosesBatch1000(benchmark::State& state) {
  const GaitModel& model = Model();
  const auto queries = Queries(model);
  Eigen::MatrixXd xs(1000, 3), poses(1000, model.NumChannels());
  for (int i = 0; i < 1000; ++i) xs.row(i) = queries[i % queries.size()].transpose();
  ModelWorkspace workspace;
  for (auto _ : state) {
    model.MeanPoses(xs, poses, &workspace);
    benchmark::DoNotOptimize(poses.data());
  }
  state.SetLabel("ms per batch = us per point");
}
BENCHMARK(BM_MeanPosesBatch1000)->Unit(benchmark::kMillisecond);

void BM_MeanPoseVarianceAndKinematics(benchmark::State& state) {
  const GaitModel& model = Model();
  const auto queries = Queries(model);
  Eigen::VectorXd pose;
  Eigen::Matrix3Xd joints;
  double variance;
  size_t i = 0;
  for (auto _ : state) {
    model.Predict(queries[i++ % queries.size()], &pose, &variance);
    model.JointPositions(pose, &joints);
    benchmark::DoNotOptimize(joints.data());
  }
}
BENCHMARK(BM_MeanPoseVarianceAndKinematics)->Unit(benchmark::kMicrosecond);

// The tracker's batch: predictive variances of 256 particles at once (one triangular
// solve with 256 right-hand sides); time per point.
void BM_VariancesBatchedPerPoint(benchmark::State& state) {
  const GaitModel& model = Model();
  const auto queries = Queries(model);
  Eigen::MatrixXd xs(queries.size(), 3);
  for (size_t i = 0; i < queries.size(); ++i) xs.row(i) = queries[i].transpose();
  for (auto _ : state) benchmark::DoNotOptimize(model.Variances(xs).data());
  state.SetItemsProcessed(state.iterations() * xs.rows());
  state.counters["seconds_per_point"] = benchmark::Counter(
      static_cast<double>(state.iterations() * xs.rows()), benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_VariancesBatchedPerPoint)->Unit(benchmark::kMillisecond);

void BM_LogPriorWithGradient(benchmark::State& state) {
  const GaitModel& model = Model();
  const auto queries = Queries(model);
  Eigen::Vector3d gradient;
  size_t i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(model.LogPrior(queries[i++ % queries.size()], &gradient));
}
BENCHMARK(BM_LogPriorWithGradient)->Unit(benchmark::kMicrosecond);

// Sequence inference (eq. 15) of subject 07's first cycle (unseen in training), without
// (0) and with (1) posture adaptation, side by side: the budget is +20%.
void BM_InferCycle(benchmark::State& state) {
  const GaitModel& model = Model();
  static const GaitDataset test =
      PrepareGaitDataset(test::CmuRoot(), "test", test::SplitTrials("test"), GaitCycleOptions{});
  PoseObservations observations;
  observations.poses_deg = test.trials[0].cycle.poses;
  InferenceOptions options;
  options.adapt_posture = state.range(0) >= 1;
  // 2: the posture prior's c and floor chosen once per model, as jgpm eval does (the choice
  // costs ~1.5 ms); 1: chosen again in every inference, as a lone call does.
  if (state.range(0) == 2) options.posture = PosturePrior::FromTrainingSet(model.data().set).Chosen();
  int iterations = 0;
  for (auto _ : state) iterations = InferLatentSequence(model, observations, options).iterations;
  const char* labels[] = {" plain", " adapted", " adapted, prior chosen once"};
  state.SetLabel(test.trials[0].id.name + labels[state.range(0)]);
  state.counters["lm_iterations"] = iterations;
}
BENCHMARK(BM_InferCycle)->Arg(0)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond);


// One evaluation of the GP objective with its gradient (mapping + dynamics, 43 channels,
// sequences of 30, synthetic smooth data on one core), exact (M = 0) against sparse with M
// inducing inputs, for N latent points: the exact one is O(N^3), the sparse O(N M^2).
void BM_ObjectiveEvaluation(benchmark::State& state) {
  static const LinearAlgebraThreadScope one_thread(1);
  const SyntheticGpProblem problem =
      MakeSyntheticGpProblem(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  ObjectiveTerms terms;
  terms.channel_scales = terms.dynamics = true;
  const GpObjective objective(problem.y, problem.sequences, nullptr, terms);
  GpParameters gradient;
  for (auto _ : state) benchmark::DoNotOptimize(objective.Evaluate(problem.params, &gradient).total);
  state.SetLabel(state.range(1) > 0 ? "sparse" : "exact");
}
BENCHMARK(BM_ObjectiveEvaluation)
    ->Args({900, 0})
    ->Args({1800, 0})
    ->ArgsProduct({{900, 1800, 3600, 10000}, {100, 200, 400}})
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace jgpm

BENCHMARK_MAIN();
