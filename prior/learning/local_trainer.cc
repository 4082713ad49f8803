#include "prior/learning/local_trainer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <random>

#include <nanoflann.hpp>

#include "io/base/error.h"
#include "prior/numerics/blas_threads.h"

namespace jgpm {
namespace {

using Clock = std::chrono::steady_clock;

// nanoflann adaptor over the rows of a matrix; must not outlive it.
struct RowsAdaptor {
  const Eigen::MatrixXd& rows;
  size_t kdtree_get_point_count() const { return static_cast<size_t>(rows.rows()); }
  double kdtree_get_pt(size_t i, size_t d) const { return rows(static_cast<int>(i), static_cast<int>(d)); }
  template <class Box>
  bool kdtree_get_bbox(Box&) const { return false; }
};
using KdTree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, RowsAdaptor>,
                                                   RowsAdaptor, 3, int>;

}  // namespace

bool LocalTrainingOptions::Check(std::string* why) const {
  const char* problem = nullptr;
  if (neighbourhood_size < 4) problem = "neighbourhood_size must be at least 4";
  else if (!(max_neighbourhood_fraction > 0 && max_neighbourhood_fraction <= 1)) problem = "max_neighbourhood_fraction must be in (0, 1]";
  else if (!(latent_step > 0) || !(hyper_step >= 0)) problem = "step sizes must be positive";
  else if (!(step_decay > 0 && step_decay <= 1)) problem = "step_decay must be in (0, 1]";
  else if (max_steps < 1) problem = "max_steps must be >= 1";
  else if (evaluation_interval < 0) problem = "evaluation_interval must be >= 0";
  else if (!(plateau_tolerance >= 0)) problem = "plateau_tolerance must be >= 0";
  else if (plateau_window < 1) problem = "plateau_window must be >= 1";
  if (problem && why) *why = problem;  // `why` may be null
  return problem == nullptr;
}

int LocalNeighbourhoodSize(int num_points, const LocalTrainingOptions& options) {
  const int cap = static_cast<int>(options.max_neighbourhood_fraction * num_points);
  return std::max(4, std::min(options.neighbourhood_size, cap));
}

std::vector<std::vector<int>> LocalNeighbourhoods(const TrainingSet& set,
                                                  const Eigen::MatrixXd& prior_coordinates, int size) {
  const int layers = set.NumLayers();
  const int per_layer_points = set.NumGaits() * set.poses_per_gait;
  const int per_layer = std::max(1, std::min(size / layers, per_layer_points));
  std::vector<Eigen::MatrixXd> layer_coordinates(layers);
  std::vector<std::unique_ptr<KdTree>> trees;
  std::vector<std::unique_ptr<RowsAdaptor>> adaptors;
  for (int l = 0; l < layers; ++l) {
    layer_coordinates[l] = prior_coordinates.middleRows(set.Row(l, 0, 0), per_layer_points);
    adaptors.push_back(std::make_unique<RowsAdaptor>(RowsAdaptor{layer_coordinates[l]}));
    trees.push_back(std::make_unique<KdTree>(3, *adaptors.back(), nanoflann::KDTreeSingleIndexAdaptorParams(10)));
  }
  std::vector<std::vector<int>> neighbourhoods(set.NumPoints());
  std::vector<int> indices(per_layer);
  std::vector<double> distances(per_layer);
  for (int i = 0; i < set.NumPoints(); ++i) {
    const TrainingPoint& point = set.points[i];
    for (int l = 0; l < layers; ++l) {
      const Eigen::Vector3d query = prior_coordinates.row(set.Row(l, point.gait, point.pose));
      const size_t found = trees[l]->knnSearch(query.data(), per_layer, indices.data(), distances.data());
      for (size_t k = 0; k < found; ++k) neighbourhoods[i].push_back(set.Row(l, 0, 0) + indices[k]);
    }
    std::sort(neighbourhoods[i].begin(), neighbourhoods[i].end());
    neighbourhoods[i].erase(std::unique(neighbourhoods[i].begin(), neighbourhoods[i].end()), neighbourhoods[i].end());
  }
  return neighbourhoods;
}

TrainingSummary TrainLocal(const GpObjective& objective,
                           const std::vector<std::vector<int>>& neighbourhoods,
                           GpParameters* params, const LocalTrainingOptions& options) {
  std::string why;
  JGPM_CHECK(options.Check(&why));
  JGPM_CHECK(static_cast<int>(neighbourhoods.size()) == objective.NumPoints());
  const auto start = Clock::now();
  TrainingSummary summary;
  summary.learning = Learning::kLocal;
  ObjectiveValue full = objective.Evaluate(*params, nullptr);
  summary.evaluations = 1;
  if (!full.ok) {
    summary.termination = Termination::kNumericalFailure;
    summary.message = full.why;
    return summary;
  }
  summary.initial_objective = full.total;
  // Steps factorise M x M matrices, where OpenBLAS's threads cost more than they give
  // (M = 120, idle 2-core machine: 2000 steps/s on one thread, 1350-1600 on two; a third
  // of that when the other core is busy). Checks of the full objective use them all.
  const int all_threads = LinearAlgebraThreads();
  const LinearAlgebraThreadScope one_thread(1);
  summary.max_jitter = full.jitter;
  const int n = objective.NumPoints();
  const int m = static_cast<int>(neighbourhoods[0].size());
  const double ratio = static_cast<double>(n) / m;
  const int interval = options.evaluation_interval > 0
                           ? options.evaluation_interval
                           : static_cast<int>(std::clamp(2 * ratio * ratio * ratio, 100.0, 1e8));
  std::mt19937_64 random(options.seed);
  std::uniform_int_distribution<int> pick(0, n - 1);

  // Adam state over the packed parameters; latent rows are only touched by the steps of
  // neighbourhoods that hold them.
  const int size = params->Size();
  const int latent = static_cast<int>(params->x.size());
  std::vector<double> x(size), g(size), first(size, 0.0), second(size, 0.0);
  std::vector<int> updates(size, 0);  // per-parameter step count for bias correction
  constexpr double kBeta1 = 0.9, kBeta2 = 0.999, kEpsilon = 1e-8;
  double latent_step = options.latent_step, hyper_step = options.hyper_step;
  params->Pack(x.data());
  GpParameters best = *params;
  double best_value = full.total;
  GpParameters gradient;
  std::vector<double> history{best_value};
  auto last_report = start, last_improvement = start;
  summary.termination = Termination::kNoConvergence;
  summary.message = "maximum number of steps reached";
  for (int step = 1; step <= options.max_steps; ++step) {
    const std::vector<int>& subset = neighbourhoods[pick(random)];
    const ObjectiveValue local = objective.EvaluateSubset(*params, subset, &gradient);
    summary.max_jitter = std::max(summary.max_jitter, local.jitter);
    ++summary.iterations;
    if (local.ok) {
      gradient.Pack(g.data());
      auto update = [&](int k, double rate) {
        if (!std::isfinite(g[k])) return;
        ++updates[k];
        first[k] = kBeta1 * first[k] + (1 - kBeta1) * g[k];
        second[k] = kBeta2 * second[k] + (1 - kBeta2) * g[k] * g[k];
        const double m_hat = first[k] / (1 - std::pow(kBeta1, updates[k]));
        const double v_hat = second[k] / (1 - std::pow(kBeta2, updates[k]));
        x[k] -= rate * m_hat / (std::sqrt(v_hat) + kEpsilon);
      };
      for (int i : subset) {
        for (int d = 0; d < 3; ++d) update(3 * i + d, latent_step);
      }
      for (int k = latent; k < size; ++k) {
        if (g[k] != 0.0) update(k, hyper_step);  // fixed ones have zero gradient
      }
      params->Unpack(x.data());
    }
    // The budget is read after every step, so Ctrl-C and --max-time act at once; when it
    // is used up, one last check brings the best parameters up to date.
    const std::string stop = options.budget.Exhausted(std::chrono::duration<double>(Clock::now() - start).count());
    if (step % interval != 0 && step != options.max_steps && stop.empty()) continue;

    {
      const LinearAlgebraThreadScope check_threads(all_threads);
      full = objective.Evaluate(*params, nullptr);
    }
    ++summary.evaluations;
    if (!full.ok) {
      summary.termination = Termination::kNumericalFailure;
      summary.message = full.why;
      break;
    }
    if (full.total < best_value) {
      best_value = full.total;
      best = *params;
      last_improvement = Clock::now();
    } else {
      latent_step *= options.step_decay;
      hyper_step *= options.step_decay;
    }
    history.push_back(best_value);
    const auto now = Clock::now();
    const double elapsed = std::chrono::duration<double>(now - start).count();
    if (options.progress &&
        std::chrono::duration<double>(now - last_report).count() >= options.progress_interval_s) {
      last_report = now;
      TrainingProgress p;
      p.stage = "local";
      p.iteration = step;
      p.max_iterations = options.max_steps;
      p.objective = full.total;
      p.jitter = summary.max_jitter;
      p.elapsed_seconds = elapsed;
      p.rate = step / elapsed;
      p.seconds_since_improvement = std::chrono::duration<double>(now - last_improvement).count();
      p.window_improvement = WindowImprovement(history, options.plateau_window);
      p.plateau_tolerance = options.plateau_tolerance;
      options.progress(p);
    }
    const int window = options.plateau_window;
    if (static_cast<int>(history.size()) > window &&
        history[history.size() - 1 - window] - best_value < options.plateau_tolerance * std::abs(best_value)) {
      summary.termination = Termination::kConverged;
      summary.message = "objective improved by less than " + std::to_string(options.plateau_tolerance) +
                        " (relative) over " + std::to_string(window) + " evaluations of " +
                        std::to_string(interval) + " steps";
      break;
    }
    if (!stop.empty()) {
      summary.termination = Termination::kStopped;
      summary.message = stop;
      break;
    }
  }
  *params = best;
  summary.final_objective = best_value;
  summary.wall_seconds = std::chrono::duration<double>(Clock::now() - start).count();
  return summary;
}

}  // namespace jgpm
