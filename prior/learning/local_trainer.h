// Topology-aware local learning (paper section V, METHOD.md section 3): repeatedly pick a
// reference point at random, take its precomputed neighbourhood of M points in the prior
// topology (within its layer and across layers), and take a gradient step on the
// objective restricted to those points, for their latent coordinates and the
// hyper-parameters. Each step costs O(M^3) instead of O(N^3).
//
// Steps are Adam steps (per-parameter step sizes from running gradient moments): a
// neighbourhood's gradient is a noisy estimate of the full one, which Adam averages. The
// paper leaves the step rule open; on the training split plain L-BFGS runs of a few
// iterations per neighbourhood overfit each patch and left the full objective 50% worse
// than Adam steps after the same time. A constant step leaves the points jittering about
// a noise floor; shrinking both step sizes whenever a check of the full objective finds no
// improvement lets them settle (mljgpm-torus on the training split: -102.5k and still
// jittering after 4 min with a constant step; converged at -102.9k in 156 s with a decay
// of 0.5, -104.4k in 151 s with 0.7, -108.3k in 303 s with 0.85).
//
// Every `evaluation_interval` steps the full objective is evaluated (value only); the
// best parameters seen are kept, and learning has converged when the best objective
// improved by less than plateau_tolerance * |f| over the last plateau_window evaluations
// (the same test as full learning's, over evaluations instead of iterations).
//
// Local learning does not reach the full objective's optimum: a neighbourhood's gradient
// is a biased estimate of the full one, since the mapping kernel's width (1) is that of
// the pose circles, so K^-1 couples every point of the tube. Averaged over all the
// neighbourhoods holding a point, the local gradient of its latent coordinates has a
// cosine of 0.6-0.9 with the full one (1800 points, M = 120), and the hyper-parameters'
// local gradients can have the opposite sign. A control-variate correction (SVRG) made
// learning diverge. Full learning (`TrainFull`) reaches far lower objectives.
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "prior/learning/objective.h"
#include "prior/learning/training_progress.h"
#include "prior/learning/training_set.h"

namespace jgpm {

struct LocalTrainingOptions {
  int neighbourhood_size = 120;             // M (the paper: 120)
  double max_neighbourhood_fraction = 0.1;  // M <= this * N
  double latent_step = 0.03;                // Adam step size for latent coordinates
  double hyper_step = 0.001;                // and for log hyper-parameters
  double step_decay = 0.7;                  // both steps times this when a check finds no improvement
  int max_steps = 5000000;
  // Steps between checks of the full objective; 0: 2 (N/M)^3, at least 100. A value-only
  // full evaluation costs about (N/M)^3 / 5 steps (0.3 s vs 0.45 ms at N = 1800, M = 120),
  // so the checks take about a tenth of the time; checking every 100 steps took three
  // quarters of it. Counted in steps, not seconds, so the same seed gives the same model.
  int evaluation_interval = 0;
  int plateau_window = 5;
  double plateau_tolerance = 1e-4;
  uint64_t seed = 1;
  double progress_interval_s = 1.0;
  ProgressCallback progress;
  TrainingBudget budget;

  bool Check(std::string* why) const;
};

// Neighbourhood of every point: the nearest points (Euclidean, prior coordinates) to its
// counterpart (same pose and gait) in each layer, an equal share per layer, found with
// nanoflann k-d trees. Each list is sorted and holds the point itself.
std::vector<std::vector<int>> LocalNeighbourhoods(const TrainingSet& set,
                                                  const Eigen::MatrixXd& prior_coordinates,
                                                  int size);

// Neighbourhood size for N points under the options (min of M and the fraction of N).
int LocalNeighbourhoodSize(int num_points, const LocalTrainingOptions& options);

TrainingSummary TrainLocal(const GpObjective& objective,
                           const std::vector<std::vector<int>>& neighbourhoods,
                           GpParameters* params, const LocalTrainingOptions& options);

}  // namespace jgpm
