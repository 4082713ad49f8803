#include "prior/learning/topology.h"

#include <set>

#include <gtest/gtest.h>

#include "io/base/error.h"

#include "prior/learning/training_set.h"
#include "prior/prior_test_support.h"

namespace jgpm {
namespace {

TrainingSet ThreeLayers() {
  return MakeTrainingSet(test::SyntheticGaitDataset(6, 12, 4), {0.4, 1.0, 1.25});
}

TEST(TrainingSet, DiversificationScalesAboutTheCycleMean) {
  const GaitDataset dataset = test::SyntheticGaitDataset(3, 10, 4);
  const TrainingSet set = MakeTrainingSet(dataset, {0.4, 1.0, 1.25});
  EXPECT_EQ(set.NumPoints(), 3 * 3 * 10);
  const Eigen::MatrixXd& original = dataset.trials[1].cycle.poses;
  const Eigen::RowVectorXd cycle_mean = original.colwise().mean();
  for (int layer = 0; layer < 3; ++layer) {
    for (int pose = 0; pose < 10; ++pose) {
      const Eigen::RowVectorXd expected =
          cycle_mean + set.layer_scales[layer] * (original.row(pose) - cycle_mean);
      EXPECT_LT((set.y_deg.row(set.Row(layer, 1, pose)) - expected).norm(), 1e-12);
      EXPECT_EQ(set.points[set.Row(layer, 1, pose)].layer, layer);
    }
  }
  // Normalised data: zero mean, unit standard deviation per channel.
  EXPECT_LT(set.y.colwise().mean().norm(), 1e-12);
  EXPECT_LT(((set.y.colwise().squaredNorm() / set.NumPoints()).array() - 1).abs().maxCoeff(), 1e-12);
}

TEST(Topology, TorusCoordinatesByHand) {
  const TrainingSet set = ThreeLayers();
  const Topology t = MakeTopology(set, TopologyOptions{});
  // Pose 0 (alpha = 0) of the gait at position 0 (beta = 0) on the middle layer (r = 1):
  // ((R + r), 0, 0) = (3, 0, 0); pose 3 of 12 (alpha = pi/2) on the outer layer: (R, 0, 1.25).
  const int g0 = t.gait_order[0];
  EXPECT_TRUE(t.coordinates.row(set.Row(1, g0, 0)).isApprox(Eigen::RowVector3d(3, 0, 0)));
  EXPECT_LT((t.coordinates.row(set.Row(2, g0, 3)) - Eigen::RowVector3d(2, 0, 1.25)).norm(), 1e-12);
  // Every point lies on its layer's torus: (sqrt(x^2 + y^2) - R)^2 + z^2 = r^2.
  for (int i = 0; i < set.NumPoints(); ++i) {
    const Eigen::Vector3d p = t.coordinates.row(i);
    const double r = t.layer_radii[set.points[i].layer];
    EXPECT_NEAR(std::pow(std::hypot(p.x(), p.y()) - 2.0, 2) + p.z() * p.z(), r * r, 1e-12);
  }
}

TEST(Topology, NeighboursAreTenWithinAndSixAcross) {
  const TrainingSet set = ThreeLayers();
  const Topology t = MakeTopology(set, TopologyOptions{});
  for (int i = 0; i < set.NumPoints(); ++i) {
    const std::vector<int>& nb = t.neighbours[i];
    ASSERT_EQ(nb.size(), 16u);
    EXPECT_EQ(std::set<int>(nb.begin(), nb.end()).size(), 16u);
    int within = 0;
    std::map<int, int> across;
    for (int j : nb) {
      EXPECT_NE(j, i);
      if (set.points[j].layer == set.points[i].layer) {
        ++within;
      } else {
        ++across[set.points[j].layer];
      }
    }
    EXPECT_EQ(within, 10);
    if (set.points[i].layer == 1) {  // middle: 3 from the outer and 3 from the inner layer
      EXPECT_EQ(across[0], 3);
      EXPECT_EQ(across[2], 3);
    } else {
      EXPECT_EQ(across[1], 6);
    }
  }
  // Within-layer neighbours of a middle-layer point: poses +/-1, +/-2 of its gait, and
  // poses -1..+1 of the gaits next to it on the gait circle.
  const int g = t.gait_order[2];
  const int i = set.Row(1, g, 5);
  std::set<std::pair<int, int>> grid;  // (pose, gait position)
  for (int j : t.neighbours[i]) {
    if (set.points[j].layer == 1) grid.insert({set.points[j].pose, t.gait_position[set.points[j].gait]});
  }
  EXPECT_EQ(grid, (std::set<std::pair<int, int>>{{3, 2}, {4, 2}, {6, 2}, {7, 2}, {4, 1}, {5, 1}, {6, 1},
                                                 {4, 3}, {5, 3}, {6, 3}}));
}

TEST(Topology, LleWeightsReconstructThePriorCoordinates) {
  for (TopologyShape shape : {TopologyShape::kTorus, TopologyShape::kCylinder}) {
    const TrainingSet set = ThreeLayers();
    TopologyOptions options;
    options.shape = shape;
    const Topology t = MakeTopology(set, options);
    double worst = 0, scale = 0;
    for (int i = 0; i < set.NumPoints(); ++i) {
      for (int d = 0; d < 3; ++d) {
        EXPECT_NEAR(t.weights[d].row(i).sum(), 1.0, 1e-12);
        double reconstruction = 0;
        for (size_t j = 0; j < t.neighbours[i].size(); ++j) {
          reconstruction += t.weights[d](i, j) * t.coordinates(t.neighbours[i][j], d);
        }
        worst = std::max(worst, std::abs(reconstruction - t.coordinates(i, d)));
        scale = std::max(scale, std::abs(t.coordinates(i, d)));
      }
    }
    // Exact up to the regularisation (1e-3 of trace C).
    EXPECT_LT(worst, 1e-2 * scale);
  }
}

TEST(Topology, CylinderOrdersGaitsAlongItsAxis) {
  const TrainingSet set = MakeTrainingSet(test::SyntheticGaitDataset(5, 12, 4), {1.0});
  TopologyOptions options;
  options.shape = TopologyShape::kCylinder;
  const Topology t = MakeTopology(set, options);
  // The synthetic gaits' amplitude grows with the gait index, so the open path is monotone.
  std::vector<int> order = t.gait_order;
  if (order.front() != 0) std::reverse(order.begin(), order.end());
  EXPECT_EQ(order, (std::vector<int>{0, 1, 2, 3, 4}));
  EXPECT_NEAR(t.coordinates(set.Row(0, t.gait_order[3], 0), 1), 1.5, 1e-12);  // delta * g
}

TEST(Topology, BadOptions) {
  const TrainingSet set = ThreeLayers();
  TopologyOptions options;
  options.gait_radius = 1.2;  // inside the outer layer's radius 1.25
  EXPECT_THROW(MakeTopology(set, options), InputError);
  // An odd cross-layer count cannot be split evenly between the middle layer's two
  // neighbours, so points would have different neighbour counts: refused, not an abort.
  TopologyOptions odd;
  odd.cross_layer_neighbours = 5;
  EXPECT_FALSE(odd.Check(nullptr));  // `why` may be null
  test::ExpectInputError([&] { MakeTopology(set, odd); }, {"cross_layer_neighbours must be even"});
}

}  // namespace
}  // namespace jgpm
