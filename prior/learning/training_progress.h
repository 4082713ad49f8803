// What long-running training reports while it runs and when it ends.
#pragma once

#include <atomic>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "prior/numerics/termination.h"

namespace jgpm {

// How a model's parameters were learnt: principal components (PCA), full-batch (O(N^3)
// per iteration), topology-aware local (the paper's), or sparse: full-batch on the
// inducing-point bound (prior/learning/sparse_gp.h), O(N M^2).
enum class Learning { kClosedForm, kFull, kLocal, kSparse };
// "closed form", "full", "local", "sparse".
std::string_view LearningName(Learning learning);
// The inverse of LearningName; false (learning untouched) for any other name.
bool ParseLearning(std::string_view name, Learning* learning);

struct TrainingProgress {
  std::string stage;          // "full", "local" or "sparse"
  int iteration = 0;          // L-BFGS iterations, or local steps
  int max_iterations = 0;
  double objective = 0;       // the full objective (local: at its last evaluation)
  double jitter = 0;          // largest Cholesky jitter so far
  double elapsed_seconds = 0;
  double rate = 0;            // iterations per second
  // The convergence test's state instead of a time left (the iteration cap is a safety
  // bound, rarely reached, so a time left computed from it is never true): seconds since
  // the objective last improved, and its relative improvement over the plateau window,
  // which ends training when below plateau_tolerance (NaN until the window has filled).
  double seconds_since_improvement = 0;
  double window_improvement = 0;
  double plateau_tolerance = 0;
};

using ProgressCallback = std::function<void(const TrainingProgress&)>;

// The best objective's relative improvement over the last `window` checks, from `history`
// (the best objective at each check): (history[end - 1 - window] - history.back()) /
// |history.back()|; NaN until history holds window + 1 values.
double WindowImprovement(const std::vector<double>& history, int window);

// When training should end early, keeping what it has learned: a wall-time budget, or an
// interrupt (the command's Ctrl-C handler sets the flag). Checked once per iteration.
struct TrainingBudget {
  double max_seconds = 0;                          // 0: no limit
  const std::atomic<bool>* interrupted = nullptr;  // may be null

  // Why training must stop now, or "" to go on.
  std::string Exhausted(double elapsed_seconds) const;
};

struct TrainingSummary {
  Learning learning = Learning::kFull;
  // A numerical failure still leaves the best parameters found before it.
  Termination termination = Termination::kNoConvergence;
  std::string message;       // detail from the optimiser
  int iterations = 0;
  int evaluations = 0;       // objective evaluations (local: of the full objective)
  double initial_objective = 0;
  double final_objective = 0;
  double max_jitter = 0;
  double wall_seconds = 0;
  // Sparse learning: inducing inputs per GP, and the exact objective of the learned
  // parameters (final_objective is the bound's), comparable with full and local learning.
  int inducing = 0;
  double exact_objective = 0;

  bool usable() const { return termination != Termination::kNumericalFailure; }
  // One line: how it ended, iterations, final objective, wall time.
  std::string BriefReport() const;
};

}  // namespace jgpm
