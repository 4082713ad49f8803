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
// than Adam steps after the same time.
//
// Every `evaluation_interval` steps the full objective is evaluated (value only); the
// best parameters seen are kept, and learning has converged when the best objective
// improved by less than plateau_tolerance * |f| over the last plateau_window evaluations
// (the same test as full learning's, over evaluations instead of iterations).
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "prior/objective.h"
#include "prior/training_progress.h"
#include "prior/training_set.h"

namespace jgpm {

struct LocalTrainingOptions {
  int neighbourhood_size = 120;             // M (the paper: 120)
  double max_neighbourhood_fraction = 0.1;  // M <= this * N
  double latent_step = 0.01;                // Adam step size for latent coordinates
  double hyper_step = 0.001;                // and for log hyper-parameters
  int max_steps = 200000;
  int evaluation_interval = 0;              // 0: one epoch, N / M steps, at least 100
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
