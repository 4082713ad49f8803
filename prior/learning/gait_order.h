// Orders the training gaits so that similar gaits are neighbours on the gait manifold
// (METHOD.md section 2): a shortest closed path (travelling salesman tour) for the torus,
// a shortest open path for the cylinder.
#pragma once

#include <vector>

#include <Eigen/Core>

namespace jgpm {

// Pairwise dissimilarity of gaits: RMS difference of their phase-aligned pose sequences.
// `gaits` holds one (poses x channels) matrix per gait, all the same size.
Eigen::MatrixXd GaitDistances(const std::vector<Eigen::MatrixXd>& gaits);

// Visiting order of a shortest closed tour through all nodes, starting at node 0 (exact:
// Held-Karp dynamic programming up to 21 nodes; beyond that, nearest-neighbour tours
// improved by 2-opt from every start node).
std::vector<int> ShortestClosedPath(const Eigen::MatrixXd& distances);

// Visiting order of a shortest open path through all nodes (either end free; exact up to
// 20 nodes, 2-opt beyond).
std::vector<int> ShortestOpenPath(const Eigen::MatrixXd& distances);

// Length of a path through `order` (closed: back to the start).
double PathLength(const Eigen::MatrixXd& distances, const std::vector<int>& order, bool closed);

}  // namespace jgpm
