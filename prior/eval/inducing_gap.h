// How many inducing inputs a learned GP model needs (issue #17): the inducing-point bound
// (prior/learning/sparse_gp.h) at the model's own latent points and hyper-parameters,
// against its exact objective, as M grows, and what one evaluation costs each way.
//
// The inducing inputs are chosen greedily, by pivoted Cholesky of each GP's noise-free
// kernel over its inputs (GreedyPivotOrder, prior/numerics/cholesky.h): each next one is
// the input the previous ones explain worst (Fine & Scheinberg 2001; the "greedy
// variance" start that Burt, Rasmussen & van der Wilk 2020 recommend for this bound's
// inducing inputs). Optionally they are then optimised, with the latent points and
// hyper-parameters held, by L-BFGS on the bound (as sparse learning moves them). The gap
// says whether sparse learning could reach this model's objective with M inputs at all:
// the bound's trace term c/(2 sigma^2) tr(K - Q) grows as the noise sigma^2 shrinks, so
// nearly noise-free poses need many inputs.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "prior/model/gait_model.h"

namespace jgpm {

struct InducingGapPoint {
  int m = 0;                   // inducing inputs per GP (the dynamics GP: at most its inputs)
  double bound = 0;            // the sparse objective (an upper bound on the exact one)
  double optimised_bound = 0;  // after optimising the inducing inputs (= bound without)
  int optimiser_iterations = 0;
  // Bound minus exact, per term (the other terms do not depend on the inducing inputs).
  double mapping_gap = 0;
  double dynamics_gap = 0;     // 0 without dynamics
  double seconds = 0;          // one evaluation with gradient, the faster of two
  // Predictions through the greedy inducing inputs (the mapping's posterior mean
  // K_xu (sigma^2 K_uu + K_un K_nu)^-1 K_un Y): their mean absolute error against the
  // training poses at the training latent points, degrees, and the time of one mean pose.
  double mean_error_deg = 0;
  double mean_seconds = 0;
  double gap() const { return mapping_gap + dynamics_gap; }
  double optimised_gap(double exact) const { return optimised_bound - exact; }
};

struct InducingGapReport {
  double exact = 0;            // the model's exact objective
  double exact_seconds = 0;    // one exact evaluation with gradient, the faster of two
  double noise_std = 0;        // the mapping's noise std (normalised channels)
  double exact_mean_error_deg = 0;  // the same for the exact mean K_x. K^-1 Y
  double exact_mean_seconds = 0;
  std::vector<InducingGapPoint> points;  // one per requested M, in the order given
};

// For a GP model (not PCA) and each M in `ms` (3 <= M <= N): InputError otherwise, or when
// an objective cannot be evaluated. With optimise_iterations > 0, at most that many
// L-BFGS iterations on the inducing inputs per M. Runs on the calling thread's
// linear-algebra threads.
InducingGapReport MeasureInducingGap(const GaitModel& model, const std::vector<int>& ms, int optimise_iterations = 0);

// The gap relative to |exact| against M (log scale), each point labelled with its
// evaluation's cost as a multiple of the exact one's, and the optimised gap where the
// inducing inputs were optimised; `title` names the model.
cv::Mat InducingGapPlot(const InducingGapReport& report, const std::string& title);

}  // namespace jgpm
