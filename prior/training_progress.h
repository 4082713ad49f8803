// What long-running training reports while it runs and when it ends.
#pragma once

#include <atomic>
#include <functional>
#include <string>

#include "prior/termination.h"

namespace jgpm {

struct TrainingProgress {
  std::string stage;          // "full", "local" or "sparse"
  int iteration = 0;          // L-BFGS iterations, or local steps
  int max_iterations = 0;
  double objective = 0;       // the full objective (local: at its last evaluation)
  double jitter = 0;          // largest Cholesky jitter so far
  double elapsed_seconds = 0;
  double rate = 0;            // iterations per second
  double seconds_left = 0;    // upper bound: at this rate until max_iterations
};

using ProgressCallback = std::function<void(const TrainingProgress&)>;

// When training should end early, keeping what it has learned: a wall-time budget, or an
// interrupt (the command's Ctrl-C handler sets the flag). Checked once per iteration.
struct TrainingBudget {
  double max_seconds = 0;                          // 0: no limit
  const std::atomic<bool>* interrupted = nullptr;  // may be null

  // Why training must stop now, or "" to go on.
  std::string Exhausted(double elapsed_seconds) const;
};

struct TrainingSummary {
  std::string learning;      // "full", "local", "sparse" or "closed form" (PCA)
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
