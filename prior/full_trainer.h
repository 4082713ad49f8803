// Full-batch MAP learning: L-BFGS (Ceres GradientProblemSolver) on the whole objective,
// O(N^3) per evaluation.
#pragma once

#include "prior/objective.h"
#include "prior/training_progress.h"

namespace jgpm {

struct FullTrainingOptions {
  int max_iterations = 5000;           // L-BFGS iterations
  double function_tolerance = 1e-7;    // stop when |df| <= tol * |f| in an iteration
  double gradient_tolerance = 1e-8;    // or max |gradient| below this
  double progress_interval_s = 1.0;    // seconds between progress reports
  ProgressCallback progress;
};

// Optimises `params` in place; the summary says how it ended.
TrainingSummary TrainFull(const GpObjective& objective, GpParameters* params,
                          const FullTrainingOptions& options);

}  // namespace jgpm
