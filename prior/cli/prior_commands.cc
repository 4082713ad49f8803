#include "prior/cli/prior_commands.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <memory>

#include "io/base/error.h"
#include "io/base/output_batch.h"
#include "io/base/png_file.h"
#include "io/base/text_reader.h"
#include "io/cli/progress.h"
#include "io/gait/data_root.h"
#include "io/gait/gait_dataset.h"
#include "io/gait/split.h"
#include "prior/eval/inducing_gap.h"
#include "prior/eval/learning_scaling.h"
#include "prior/model/latent_plot.h"
#include "prior/model/model_file.h"
#include "prior/model/model_report.h"
#include "prior/model/train.h"
#include "prior/motion/synthesis.h"
#include "prior/numerics/blas_threads.h"

namespace jgpm::cli {
namespace {

struct TrainArguments {
  std::string model = "mljgpm-torus";
  std::string out;
  std::string split = "train";
  std::string dataset;
  std::string data;
  std::string learning = "full";
  int inducing = 100;
  uint64_t seed = 1;
  int threads = 0;
  int max_iterations = 0;
  double max_time = 0;
  int neighbourhood = 0;
  double sigma2 = 0.01;
  std::string start;
};

// The first Ctrl-C (or SIGTERM) ends training early and the model learned so far is still
// written; the handler then steps aside so a second one kills the process.
std::atomic<bool> interrupted{false};
extern "C" void OnInterrupt(int signal) {
  interrupted = true;
  std::signal(signal, SIG_DFL);
}

void RunTrain(const TrainArguments& a) {
  TrainingOptions options;
  if (!ParseModelKind(a.model, &options.kind)) {
    ThrowInputError("--model " + a.model, "expected one of " + ModelKindList());
  }
  JGPM_CHECK(ParseLearning(a.learning, &options.learning));  // CLI11 checked the name
  options.inducing = a.inducing;
  options.seed = a.seed;
  options.threads = ThreadsOrAllCores(a.threads);
  options.topology_sigma2 = a.sigma2;
  if (a.max_iterations > 0) {  // L-BFGS iterations, or local steps
    options.full.max_iterations = a.max_iterations;
    options.local.max_steps = a.max_iterations;
  }
  if (a.neighbourhood > 0) {  // explicit: exactly this many, not capped at 10% of N
    options.local.neighbourhood_size = a.neighbourhood;
    options.local.max_neighbourhood_fraction = 1.0;
  }
  ProgressLine line("train");
  // No time left: the iteration cap is a safety bound, so a time left from it is never
  // true. Instead, how the convergence test stands: the last improvement's age and the
  // window's relative gain against the tolerance that ends training.
  options.progress = [&line](const TrainingProgress& p) {
    char detail[192];
    const int used = std::snprintf(detail, sizeof(detail), "(%s)  objective %.7g  jitter %.1g  improved %.0f s ago",
                                   p.stage.c_str(), p.objective, p.jitter, p.seconds_since_improvement);
    if (std::isfinite(p.window_improvement)) {
      std::snprintf(detail + used, sizeof(detail) - used, ", window gain %.1e (stops below %.0e)",
                    p.window_improvement, p.plateau_tolerance);
    }
    line.Update(p.iteration, -1, p.stage == "local" ? "steps" : "iterations", detail);
  };
  options.budget.max_seconds = a.max_time;
  options.budget.interrupted = &interrupted;

  // A prepared dataset brings its own data root (for the reference skeleton); --data
  // overrides it.
  const std::optional<std::string> data_flag = a.data.empty() ? std::nullopt : std::optional(a.data);
  GaitDataset dataset;
  std::filesystem::path root;
  if (!a.dataset.empty()) {
    dataset = ReadGaitDataset(a.dataset);
    root = data_flag ? ResolveDataRoot(data_flag) : std::filesystem::path(dataset.data_root);
  } else {
    root = ResolveDataRoot(data_flag);
    dataset = PrepareGaitDataset(root, a.split, ReadSplit(ResolveSplitPath(a.split, JGPM_SPLITS_DIR)), GaitCycleOptions{});
  }
  const ReferenceSkeleton skeleton = ChooseReferenceSkeleton(dataset, root);
  if (!a.start.empty()) {  // the same kind on the same cycles, or its parameters mean nothing here
    const std::unique_ptr<GaitModel> start = ReadModelFile(a.start);
    std::vector<std::string> ids;
    for (const GaitTrial& t : dataset.trials) {
      if (t.cycle.clean) ids.push_back(t.id.name);
    }
    if (start->kind() != options.kind || start->data().set.gait_ids != ids) {
      ThrowInputError("--start " + a.start, "is not a " + a.model + " model trained on the clean cycles of " +
                                                dataset.split + "; start from a model of the same kind and trials");
    }
    options.start = start->data().params;
  }
  std::printf("training %s (%s learning) on %d clean gait cycles of %s\n", a.model.c_str(), a.learning.c_str(),
              dataset.NumClean(), dataset.split.c_str());
  std::fflush(stdout);
  interrupted = false;
  std::signal(SIGINT, OnInterrupt);
  std::signal(SIGTERM, OnInterrupt);
  const std::unique_ptr<GaitModel> model = TrainGaitModel(dataset, skeleton, options);
  std::signal(SIGINT, SIG_DFL);
  std::signal(SIGTERM, SIG_DFL);
  line.Finish();
  WriteModelFile(a.out, *model);
  std::printf("%swrote %s\n", DescribeModel(*model).c_str(), a.out.c_str());
  if (!model->data().summary.usable()) {
    std::fprintf(stderr, "jgpm: warning: training ended in a numerical failure (%s); the model written is the best "
                 "found before it\n", model->data().summary.message.c_str());
  }
}

struct SynthArguments {
  std::string model;
  std::string path = "outer-spiral";
  std::string out;
  std::string png;
  SynthesisOptions options;
};

void RunSynth(const SynthArguments& a) {
  SynthesisPath path;
  ParseSynthesisPath(a.path, &path);
  const std::string extension = std::filesystem::path(a.out).extension().string();
  if (extension != ".amc" && extension != ".bvh") ThrowInputError("--out " + a.out, "expected a .amc or .bvh file name");
  const auto model = ReadModelFile(a.model);
  const SynthesisResult result = Synthesise(*model, path, a.options);
  const Motion motion = PosesToMotion(*model, result.poses_deg, a.options.frames_per_second);
  for (const auto& file : WriteSynthesis(model->skeleton(), model->data().skeleton_asf, motion, a.out, a.png)) {
    std::printf("wrote %s\n", file.string().c_str());
  }
}

struct ScalingArguments {
  std::vector<int> n = {900, 1800, 3600, 10000};
  std::vector<int> m = {100, 200, 400};
  int exact_max = 3600;
  int repeats = 3;
  int threads = 1;
  double converge_time = 0;  // > 0: also learn to convergence, at most this long per point
  std::string out;
};

void RunScaling(const ScalingArguments& a) {
  for (const int n : a.n) {
    if (n < 30) ThrowInputError("--n " + std::to_string(n), "expected at least 30 latent points (one cycle)");
    for (const int m : a.m) {
      if (m < 3 || m > n) ThrowInputError("--m " + std::to_string(m), "expected 3 <= M <= N (" + std::to_string(n) + ")");
    }
  }
  const std::filesystem::path out(a.out);
  std::filesystem::create_directories(out);
  const LinearAlgebraThreadScope threads(a.threads);
  std::vector<ScalingPoint> points;
  std::string csv = "n,m,seconds_per_evaluation,objective\n";
  for (const int n : a.n) {
    std::vector<int> ms = a.m;
    if (n <= a.exact_max) ms.insert(ms.begin(), 0);
    for (const int m : ms) {
      const ScalingPoint p = TimeObjectiveEvaluation(n, m, a.repeats);
      points.push_back(p);
      std::printf("N %6d  %-12s %10.2f ms per evaluation\n", n, m ? ("M " + std::to_string(m)).c_str() : "exact",
                  p.seconds * 1e3);
      std::fflush(stdout);
      csv += std::to_string(n) + "," + std::to_string(m) + "," + std::to_string(p.seconds) + "," +
             std::to_string(p.objective) + "\n";
    }
  }
  OutputBatch batch;
  if (a.converge_time > 0) {
    std::string converge = "n,m,seconds,iterations,termination,initial_objective,final_objective\n";
    for (const ScalingPoint& p : points) {
      const ConvergencePoint c = TimeToConverge(p.n, p.m, a.converge_time);
      const std::string how(TerminationName(c.termination));
      std::printf("N %6d  %-12s learning: %s after %d iterations, %.1f s, objective %.1f -> %.1f\n", c.n,
                  c.m ? ("M " + std::to_string(c.m)).c_str() : "exact", how.c_str(), c.iterations, c.seconds,
                  c.initial_objective, c.final_objective);
      std::fflush(stdout);
      char row[200];
      std::snprintf(row, sizeof(row), "%d,%d,%.3f,%d,%s,%.6f,%.6f\n", c.n, c.m, c.seconds, c.iterations, how.c_str(),
                    c.initial_objective, c.final_objective);
      converge += row;
    }
    batch.Add(out / "convergence.csv", converge);
  }
  batch.Add(out / "scaling.csv", csv);
  batch.Add(out / "scaling.png", EncodePng(ScalingPlot(points), "scaling.png"));
  for (const auto& file : batch.Commit()) std::printf("wrote %s\n", file.string().c_str());
}

struct InducingGapArguments {
  std::string model;
  std::vector<int> m = {100, 200, 400, 600, 800, 1200};
  int optimise_iterations = 0;
  int threads = 0;
  std::string out;
};

void RunInducingGap(const InducingGapArguments& a) {
  const std::unique_ptr<GaitModel> model = ReadModelFile(a.model);
  const int n = model->data().set.NumPoints();
  std::vector<int> ms;  // the model's N caps the list, so one default fits every model
  for (const int m : a.m) ms.push_back(std::min(m, n));
  std::sort(ms.begin(), ms.end());
  ms.erase(std::unique(ms.begin(), ms.end()), ms.end());
  const LinearAlgebraThreadScope threads(ThreadsOrAllCores(a.threads));
  const InducingGapReport r = MeasureInducingGap(*model, ms, a.optimise_iterations);
  const std::string kind(ModelKindName(model->kind())), learning(LearningName(model->data().summary.learning));
  std::printf("%s (%s learning), N %d: exact objective %.1f, %.3f s per evaluation with gradient; noise std %.3g\n"
              "exact mean poses: %.4f deg mean error at the training latents, %.2f us per pose\n",
              kind.c_str(), learning.c_str(), n, r.exact, r.exact_seconds, r.noise_std, r.exact_mean_error_deg,
              r.exact_mean_seconds * 1e6);
  std::printf("%6s %14s %12s %9s %12s %12s %12s %9s %8s %10s %8s\n", "M", "bound", "gap", "gap/|f|", "mapping",
              "dynamics", "optimised", "s/eval", "x exact", "mean (deg)", "us/pose");
  std::string csv = "m,bound,exact,gap,relative_gap,mapping_gap,dynamics_gap,optimised_gap,optimiser_iterations,"
                    "seconds_per_evaluation,exact_seconds_per_evaluation,mean_error_deg,exact_mean_error_deg,"
                    "seconds_per_mean_pose,exact_seconds_per_mean_pose\n";
  for (const InducingGapPoint& p : r.points) {
    std::printf("%6d %14.1f %12.1f %9.2e %12.1f %12.1f %12.1f %9.3f %8.2f %10.4f %8.2f\n", p.m, p.bound, p.gap(),
                p.gap() / std::abs(r.exact), p.mapping_gap, p.dynamics_gap, p.optimised_gap(r.exact), p.seconds,
                p.seconds / r.exact_seconds, p.mean_error_deg, p.mean_seconds * 1e6);
    char row[400];
    std::snprintf(row, sizeof(row), "%d,%.6f,%.6f,%.6f,%.6e,%.6f,%.6f,%.6f,%d,%.6f,%.6f,%.6e,%.6e,%.6e,%.6e\n", p.m,
                  p.bound, r.exact, p.gap(), p.gap() / std::abs(r.exact), p.mapping_gap, p.dynamics_gap,
                  p.optimised_gap(r.exact), p.optimiser_iterations, p.seconds, r.exact_seconds, p.mean_error_deg,
                  r.exact_mean_error_deg, p.mean_seconds, r.exact_mean_seconds);
    csv += row;
  }
  std::filesystem::create_directories(a.out);  // after the measurement, which may refuse the model
  OutputBatch batch;
  batch.Add(std::filesystem::path(a.out) / "inducing_gap.csv", csv);
  char title[200];
  std::snprintf(title, sizeof(title), "%s, %s learning, N %d: exact objective %.0f, noise std %.3g",
                kind.c_str(), learning.c_str(), n, r.exact, r.noise_std);
  batch.Add(std::filesystem::path(a.out) / "inducing_gap.png", EncodePng(InducingGapPlot(r, title), "inducing_gap.png"));
  for (const auto& file : batch.Commit()) std::printf("wrote %s\n", file.string().c_str());
}

}  // namespace

// `bench learning` and `bench inducing`: what sparse learning costs and what it can reach.
void AddPriorBenches(CLI::App* bench) {
  auto a = std::make_shared<ScalingArguments>();
  CLI::App* learning = bench->add_subcommand(
      "learning", "Time one objective evaluation (exact and sparse), and optionally learning to convergence, against N on "
      "synthetic data; scaling.csv, scaling.png");
  learning->add_option("--n", a->n, "latent points N (repeat or comma-separate)")->delimiter(',')->capture_default_str();
  learning->add_option("--m", a->m, "inducing inputs M (repeat or comma-separate)")->delimiter(',')->capture_default_str();
  learning->add_option("--exact-max", a->exact_max, "time the exact O(N^3) objective up to this N")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  learning->add_option("--repeats", a->repeats, "timed evaluations per point (the fastest is kept)")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
  learning->add_option("--threads", a->threads, "linear-algebra threads")->check(CLI::Range(1, 256))->capture_default_str();
  learning->add_option("--converge-time", a->converge_time,
                       "also learn each point to convergence (L-BFGS as `train`), at most this many seconds each; "
                       "convergence.csv")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  learning->add_option("--out", a->out, "folder for scaling.csv, scaling.png (and convergence.csv)")->required();
  learning->callback([a] { RunScaling(*a); });

  auto g = std::make_shared<InducingGapArguments>();
  CLI::App* inducing = bench->add_subcommand(
      "inducing", "The sparse bound at a model's own parameters against its exact objective, as M grows; "
                  "inducing_gap.csv, inducing_gap.png");
  inducing->add_option("--model", g->model, "a GP model file (JSON)")->required();
  inducing->add_option("--m", g->m, "inducing inputs M per GP (repeat or comma-separate; capped at N)")
      ->delimiter(',')
      ->check(CLI::Range(3, 1000000))
      ->capture_default_str();
  inducing->add_option("--optimise-iterations", g->optimise_iterations,
                       "then optimise the inducing inputs alone (L-BFGS, at most this many iterations per M)")
      ->check(CLI::Range(0, 100000))
      ->capture_default_str();
  inducing->add_option("--threads", g->threads, "linear-algebra threads (0: all cores)")
      ->check(CLI::Range(0, 256))
      ->capture_default_str();
  inducing->add_option("--out", g->out, "folder for inducing_gap.csv and inducing_gap.png")->required();
  inducing->callback([g] { RunInducingGap(*g); });
}

void AddPriorCommands(CLI::App& app) {
  auto a = std::make_shared<TrainArguments>();
  CLI::App* train = app.add_subcommand("train", "Learn a gait prior from a split's walking trials");
  train->add_option("--model", a->model, "model kind: " + ModelKindList())->capture_default_str();
  train->add_option("--out", a->out, "model file to write (JSON)")->required();
  train->add_option("--split", a->split, "split name (datasets_scripts/splits/NAME.txt) or file")->capture_default_str();
  train->add_option("--dataset", a->dataset, "a prepared dataset (`jgpm data cycles`) instead of --split");
  train->add_option("--data", a->data, "data root (default: $JGPM_DATA, ./data/cmu, ../shared/data/cmu)");
  train->add_option("--learning", a->learning,
                    "full-batch L-BFGS, topology-aware local learning, or full-batch on an inducing-point "
                    "bound (sparse, O(N M^2))")
      ->check(CLI::IsMember({"full", "local", "sparse"}))
      ->capture_default_str();
  train->add_option("--inducing", a->inducing, "sparse learning: inducing inputs per GP (M, 3..N)")
      ->check(CLI::Range(3, 1000000))
      ->capture_default_str();
  train->add_option("--seed", a->seed, "random seed (local learning)")->capture_default_str();
  train->add_option("--threads", a->threads, "linear-algebra threads (0: all cores)")
      ->check(CLI::Range(0, 256))
      ->capture_default_str();
  train->add_option("--max-iterations", a->max_iterations,
                    "L-BFGS iterations (full) or steps (local) at most (default: 5000 iterations, 5000000 steps)")
      ->check(CLI::Range(1, 100000000));
  train->add_option("--neighbourhood", a->neighbourhood,
                    "local learning: points per neighbourhood (default: 120, at most 10% of N)")
      ->check(CLI::Range(4, 100000));
  train->add_option("--max-time", a->max_time,
                    "stop after this many seconds and write the model learned so far (0: no limit; "
                    "Ctrl-C does the same)")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  train->add_option("--topology-sigma2", a->sigma2, "sigma^2 of the LLE topology energy")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  train->add_option("--start", a->start,
                    "start from this model's latent points and hyper-parameters (same kind and trials): continues "
                    "a training that was stopped, or refines one learning with another");
  train->callback([a] { RunTrain(*a); });

  auto info_model = std::make_shared<std::string>();
  CLI::App* model_command = app.add_subcommand("model", "Trained gait models");
  model_command->require_subcommand(1);
  CLI::App* info = model_command->add_subcommand("info", "Kind, hyper-parameters, training summary and reconstruction error");
  info->add_option("MODEL", *info_model, "model file")->required();
  info->callback([info_model] { std::fputs(DescribeModel(*ReadModelFile(*info_model)).c_str(), stdout); });

  auto plot_model = std::make_shared<std::string>();
  auto plot_out = std::make_shared<std::string>();
  CLI::App* plot = app.add_subcommand("plot", "Pictures of trained models");
  plot->require_subcommand(1);
  CLI::App* latent = plot->add_subcommand("latent", "Latent points and predictive variance slices (PNG)");
  latent->add_option("MODEL", *plot_model, "model file")->required();
  latent->add_option("--out", *plot_out, "PNG to write")->required();
  latent->callback([plot_model, plot_out] {
    const auto model = ReadModelFile(*plot_model);
    PlotLatentSpace(*model, *plot_out);
    std::printf("wrote %s\n", plot_out->c_str());
  });

  auto s = std::make_shared<SynthArguments>();
  CLI::App* synth = app.add_subcommand("synth", "Synthesise walking by sampling a JGPM-family latent space (paper Fig. 14)");
  synth->add_option("--model", s->model, "model file (jgpm, mljgpm-torus or mljgpm-cyl)")->required();
  synth->add_option("--path", s->path,
                    "line: one pose, stride growing across the layers; outer-/inner-spiral: walking with the "
                    "largest / smallest strides")
      ->check(CLI::IsMember({"line", "outer-spiral", "inner-spiral"}))
      ->capture_default_str();
  synth->add_option("--out", s->out, "OUT.amc (with OUT.asf beside it) or OUT.bvh")->required();
  synth->add_option("--png", s->png, "also a strip of stick figures");
  synth->add_option("--frames", s->options.frames, "frames")->check(CLI::Range(2, 100000))->capture_default_str();
  synth->add_option("--fps", s->options.frames_per_second, "frame rate written")->check(CLI::PositiveNumber)->capture_default_str();
  synth->add_option("--cycles", s->options.cycles, "spirals: walking cycles")->check(CLI::PositiveNumber)->capture_default_str();
  synth->add_option("--gait-span", s->options.gait_span, "spirals: gait positions travelled")->capture_default_str();
  synth->add_option("--phase", s->options.phase, "line: pose phase in [0, 1)")->check(CLI::Range(0.0, 1.0))->capture_default_str();
  synth->add_option("--gait", s->options.gait, "gait position (line) or start (spirals)")->capture_default_str();
  synth->callback([s] { RunSynth(*s); });
}

}  // namespace jgpm::cli
