#include "prior/learning/topology.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>

#include "io/base/error.h"
#include "prior/learning/gait_order.h"

namespace jgpm {
namespace {

constexpr double kTwoPi = 2 * std::numbers::pi;

// Grid displacement between pose/gait positions, wrapped where the manifold is closed.
int Wrap(int delta, int period) {
  delta %= period;
  if (delta > period / 2) delta -= period;
  if (delta < -period / 2) delta += period;
  return delta;
}

// The `count` points of `layer` nearest to grid position (pose, gait) in the grid metric
// |d_pose|^2 + (1.01 d_gait)^2 (the 1.01 prefers the pose direction on ties), skipping
// `self`. Ties are broken by grid order, so the choice is deterministic.
std::vector<int> GridNeighbours(const TrainingSet& set, const Topology& t, int layer, int pose,
                                int gait_pos, int count, int self) {
  const int poses = set.poses_per_gait, gaits = set.NumGaits();
  struct Candidate {
    double distance;
    int row;
  };
  std::vector<Candidate> candidates;
  for (int g = 0; g < gaits; ++g) {
    int dg = g - gait_pos;
    if (t.shape == TopologyShape::kTorus) dg = Wrap(dg, gaits);
    for (int p = 0; p < poses; ++p) {
      const int row = set.Row(layer, t.gait_order[g], p);
      if (row == self) continue;
      const int dp = Wrap(p - pose, poses);
      candidates.push_back({dp * dp + 1.0201 * dg * dg, row});
    }
  }
  count = std::min<int>(count, static_cast<int>(candidates.size()));
  std::partial_sort(candidates.begin(), candidates.begin() + count, candidates.end(),
                    [](const Candidate& a, const Candidate& b) {
                      return a.distance < b.distance || (a.distance == b.distance && a.row < b.row);
                    });
  std::vector<int> rows;
  for (int k = 0; k < count; ++k) rows.push_back(candidates[k].row);
  return rows;
}

// Weights w (summing to 1) minimising |t_i - sum_j w_j t_j|^2 in one dimension, LLE style:
// C = c c^T with c_j = t_i - t_j, regularised by reg * trace(C) on the diagonal. Closed
// form of (c c^T + e I)^-1 1: (1 - c (c.1) / (e + |c|^2)) / e, then normalised.
Eigen::VectorXd LleWeights(const Eigen::VectorXd& c, double regularization) {
  const int k = static_cast<int>(c.size());
  const double c2 = c.squaredNorm();
  if (c2 < 1e-24) return Eigen::VectorXd::Constant(k, 1.0 / k);
  const double e = regularization * c2;
  const Eigen::VectorXd u = Eigen::VectorXd::Ones(k) - c * (c.sum() / (e + c2));
  return u / u.sum();
}

}  // namespace

bool TopologyOptions::Check(std::string* why) const {
  const char* problem = nullptr;
  if (!(gait_radius > 0)) problem = "gait_radius must be > 0";
  else if (!(gait_spacing > 0)) problem = "gait_spacing must be > 0";
  else if (within_layer_neighbours < 1) problem = "within_layer_neighbours must be >= 1";
  else if (cross_layer_neighbours < 0 || cross_layer_neighbours % 2 != 0) {
    // The middle layer takes half from each adjacent layer: every point then has as many.
    problem = "cross_layer_neighbours must be even and >= 0";
  } else if (!(lle_regularization > 0)) problem = "lle_regularization must be > 0";
  if (problem && why) *why = problem;  // `why` may be null
  return problem == nullptr;
}

Eigen::Vector3d Topology::PriorPoint(double alpha, double gait, double radius) const {
  const int gaits = static_cast<int>(gait_order.size());
  if (shape == TopologyShape::kTorus) {
    const double beta = kTwoPi * gait / gaits;
    const double ring = options.gait_radius + radius * std::cos(alpha);
    return {ring * std::cos(beta), ring * std::sin(beta), radius * std::sin(alpha)};
  }
  return {radius * std::cos(alpha), options.gait_spacing * gait, radius * std::sin(alpha)};
}

Topology MakeTopology(const TrainingSet& set, const TopologyOptions& options) {
  std::string why;
  if (!options.Check(&why)) ThrowInputError("topology options", why);
  Topology t;
  t.shape = options.shape;
  t.options = options;
  const int gaits = set.NumGaits(), poses = set.poses_per_gait, layers = set.NumLayers();
  t.layer_radii = set.layer_scales;
  if (t.shape == TopologyShape::kTorus) {
    const double largest = *std::max_element(t.layer_radii.begin(), t.layer_radii.end());
    if (options.gait_radius <= largest) {
      ThrowInputError("topology options", "gait_radius must exceed the largest layer radius " +
                                              std::to_string(largest) + " (else the torus crosses itself)");
    }
  }

  // Gait order from the original (first scale 1, else first) layer's cycles.
  int reference_layer = 0;
  for (int l = 0; l < layers; ++l) {
    if (set.layer_scales[l] == 1.0) reference_layer = l;
  }
  std::vector<Eigen::MatrixXd> cycles;
  for (int g = 0; g < gaits; ++g) {
    cycles.push_back(set.y.middleRows(set.Row(reference_layer, g, 0), poses));
  }
  const Eigen::MatrixXd distances = GaitDistances(cycles);
  t.gait_order = t.shape == TopologyShape::kTorus ? ShortestClosedPath(distances)
                                                  : ShortestOpenPath(distances);
  t.gait_position.assign(gaits, 0);
  for (int k = 0; k < gaits; ++k) t.gait_position[t.gait_order[k]] = k;

  const int n = set.NumPoints();
  t.coordinates.resize(n, 3);
  for (int i = 0; i < n; ++i) {
    const TrainingPoint& point = set.points[i];
    const double alpha = kTwoPi * point.pose / poses;
    t.coordinates.row(i) =
        t.PriorPoint(alpha, t.gait_position[point.gait], t.layer_radii[point.layer]).transpose();
  }

  // Layers ordered by radius: a layer's cross-layer neighbours come from the layers just
  // inside and outside it.
  std::vector<int> by_radius(layers);
  std::iota(by_radius.begin(), by_radius.end(), 0);
  std::sort(by_radius.begin(), by_radius.end(),
            [&](int a, int b) { return t.layer_radii[a] < t.layer_radii[b]; });
  t.neighbours.resize(n);
  for (int i = 0; i < n; ++i) {
    const TrainingPoint& point = set.points[i];
    const int gait_pos = t.gait_position[point.gait];
    std::vector<int> rows = GridNeighbours(set, t, point.layer, point.pose, gait_pos,
                                           options.within_layer_neighbours, i);
    const int rank = static_cast<int>(std::find(by_radius.begin(), by_radius.end(), point.layer) - by_radius.begin());
    std::vector<int> adjacent;
    if (rank > 0) adjacent.push_back(by_radius[rank - 1]);
    if (rank + 1 < layers) adjacent.push_back(by_radius[rank + 1]);
    for (int layer : adjacent) {
      const int count = options.cross_layer_neighbours / static_cast<int>(adjacent.size());
      const std::vector<int> cross = GridNeighbours(set, t, layer, point.pose, gait_pos, count, -1);
      rows.insert(rows.end(), cross.begin(), cross.end());
    }
    t.neighbours[i] = rows;
  }

  const int k = static_cast<int>(t.neighbours[0].size());
  for (int d = 0; d < 3; ++d) t.weights[d].resize(n, k);
  for (int i = 0; i < n; ++i) {
    JGPM_CHECK(static_cast<int>(t.neighbours[i].size()) == k);
    for (int d = 0; d < 3; ++d) {
      Eigen::VectorXd c(k);
      for (int j = 0; j < k; ++j) c[j] = t.coordinates(i, d) - t.coordinates(t.neighbours[i][j], d);
      t.weights[d].row(i) = LleWeights(c, options.lle_regularization).transpose();
    }
  }
  return t;
}

}  // namespace jgpm
