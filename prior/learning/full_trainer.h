// Full-batch MAP learning: L-BFGS (Ceres GradientProblemSolver) on the whole objective,
// O(N^3) per evaluation; or O(N M^2) when the parameters carry inducing inputs (sparse
// learning, prior/learning/sparse_gp.h), which are optimised with the rest.
#pragma once

#include "prior/learning/objective.h"
#include "prior/learning/training_progress.h"

namespace jgpm {

struct FullTrainingOptions {
  int max_iterations = 5000;           // L-BFGS iterations
  // Converged when the objective improved by less than plateau_tolerance * |f| over the
  // last plateau_window iterations (L-BFGS on these objectives creeps for thousands of
  // iterations at a few nats each; a per-iteration test would never fire).
  int plateau_window = 50;
  double plateau_tolerance = 1e-4;
  double gradient_tolerance = 1e-8;    // or max |gradient| below this
  double progress_interval_s = 1.0;    // seconds between progress reports
  ProgressCallback progress;
  TrainingBudget budget;
};

// Optimises `params` in place; the summary says how it ended.
TrainingSummary TrainFull(const GpObjective& objective, GpParameters* params,
                          const FullTrainingOptions& options);

}  // namespace jgpm
