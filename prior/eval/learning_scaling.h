// How the cost of learning grows with the number of latent points N (issue #17): one
// evaluation of the GP objective with its gradient, and learning until it converges, exact
// (O(N^3) per evaluation) against the inducing-point bound with M inducing inputs
// (O(N M^2)), on synthetic walking-like data of any size, and a log-log chart of the first.
#pragma once

#include <vector>

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "prior/learning/objective.h"
#include "prior/numerics/termination.h"

namespace jgpm {

// A GPDM-style problem of N latent points on a cycle of 30 poses per sequence, 43 smooth
// output channels with noise, the dynamics GP on (fixed seed), and its parameters; with
// M > 0 inducing inputs for both GPs at evenly spaced latent points.
struct SyntheticGpProblem {
  Eigen::MatrixXd y;
  std::vector<Sequence> sequences;
  GpParameters params;
};
SyntheticGpProblem MakeSyntheticGpProblem(int n, int m);

struct ScalingPoint {
  int n = 0;
  int m = 0;                  // inducing inputs; 0: the exact objective
  double seconds = 0;         // per evaluation with gradient, the fastest of the repeats
  double objective = 0;       // the value evaluated (a check that it ran)
};

// Times `repeats` evaluations (after one warm-up) on the calling thread's linear-algebra
// threads. InputError if the objective cannot be evaluated.
ScalingPoint TimeObjectiveEvaluation(int n, int m, int repeats);

struct ConvergencePoint {
  int n = 0;
  int m = 0;                  // inducing inputs; 0: the exact objective
  double seconds = 0;         // wall time of the learning
  int iterations = 0;         // L-BFGS iterations
  Termination termination = Termination::kNoConvergence;
  double initial_objective = 0, final_objective = 0;  // the bound's for M > 0
};

// Full-batch L-BFGS on the synthetic problem's objective (M = 0) or bound, from its
// parameters, as `jgpm train --learning full|sparse` learns (same trainer, stopping rule
// and defaults), until it converges or `max_seconds` pass. Runs on the calling thread's
// linear-algebra threads.
ConvergencePoint TimeToConverge(int n, int m, double max_seconds);

// Seconds per evaluation against N, log-log, one line per M (and the exact objective), with
// a line of slope 1 (linear growth) for reference.
cv::Mat ScalingPlot(const std::vector<ScalingPoint>& points);

}  // namespace jgpm
