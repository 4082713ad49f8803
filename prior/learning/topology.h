// Topology priors of the JGPM family (METHOD.md section 2): where each training point
// should sit on a torus or cylinder (pose angle around the pose circle, gait along the
// gait manifold, one concentric layer per stride scale), which points are its topology
// neighbours, and the LLE weights that reconstruct its prior coordinates from theirs.
#pragma once

#include <array>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "prior/learning/training_set.h"

namespace jgpm {

enum class TopologyShape { kTorus, kCylinder };

struct TopologyOptions {
  TopologyShape shape = TopologyShape::kTorus;
  // Torus: radius R of the gait circle. The middle layer's pose circle has radius 1 and
  // each layer's radius is its stride scale (0.4, 1, 1.25), so R must exceed the largest.
  double gait_radius = 2.0;
  // Cylinder: distance delta between adjacent gaits along the axis (METHOD: 0.5).
  double gait_spacing = 0.5;
  // Topology neighbours per point: within its layer, and from the adjacent layers (split
  // evenly between them: the middle layer takes 3 + 3, an outer or inner layer 6).
  int within_layer_neighbours = 10;
  int cross_layer_neighbours = 6;
  // LLE regularisation: this times trace(C) is added to C's diagonal (C has rank one).
  double lle_regularization = 1e-3;

  bool Check(std::string* why) const;
};

struct Topology {
  TopologyShape shape = TopologyShape::kTorus;
  TopologyOptions options;
  // gait_order[k] is the gait at position k along the gait manifold; gait_position is its
  // inverse. Closed (torus) or open (cylinder) shortest path over GaitDistances.
  std::vector<int> gait_order;
  std::vector<int> gait_position;
  std::vector<double> layer_radii;   // pose-circle radius of each layer (= its scale)
  Eigen::MatrixXd coordinates;       // N x 3 prior coordinates t
  // neighbours[i] and, per latent dimension, weights[d](i, k) for neighbour k of point i;
  // each row of weights[d] sums to 1.
  std::vector<std::vector<int>> neighbours;
  std::array<Eigen::MatrixXd, 3> weights;

  // Prior coordinates of pose angle `alpha` (radians), gait coordinate `gait` (a position
  // along the gait manifold, 0 .. num_gaits, fractional allowed) at pose radius `radius`.
  Eigen::Vector3d PriorPoint(double alpha, double gait, double radius) const;
};

// InputError for bad options (naming the option).
Topology MakeTopology(const TrainingSet& set, const TopologyOptions& options);

}  // namespace jgpm
