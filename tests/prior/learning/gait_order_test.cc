#include "prior/learning/gait_order.h"

#include <algorithm>
#include <numbers>
#include <numeric>
#include <random>

#include <gtest/gtest.h>

namespace jgpm {
namespace {

Eigen::MatrixXd RandomDistances(int n, unsigned seed) {
  std::srand(seed);
  const Eigen::MatrixXd points = Eigen::MatrixXd::Random(n, 4);
  Eigen::MatrixXd d(n, n);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) d(i, j) = (points.row(i) - points.row(j)).norm();
  }
  return d;
}

// Oracle: every permutation.
double BruteForce(const Eigen::MatrixXd& d, bool closed) {
  std::vector<int> order(d.rows());
  std::iota(order.begin(), order.end(), 0);
  double best = 1e300;
  do {
    best = std::min(best, PathLength(d, order, closed));
  } while (std::next_permutation(order.begin() + (closed ? 1 : 0), order.end()));
  return best;
}

bool IsPermutation(std::vector<int> order, int n) {
  std::sort(order.begin(), order.end());
  for (int i = 0; i < n; ++i) {
    if (order[i] != i) return false;
  }
  return static_cast<int>(order.size()) == n;
}

TEST(GaitOrder, ClosedAndOpenPathsAreShortest) {
  for (int n = 2; n <= 8; ++n) {
    for (unsigned seed = 0; seed < 5; ++seed) {
      const Eigen::MatrixXd d = RandomDistances(n, 100 * n + seed);
      const std::vector<int> closed = ShortestClosedPath(d);
      const std::vector<int> open = ShortestOpenPath(d);
      ASSERT_TRUE(IsPermutation(closed, n));
      ASSERT_TRUE(IsPermutation(open, n));
      EXPECT_EQ(closed[0], 0);
      EXPECT_NEAR(PathLength(d, closed, true), BruteForce(d, true), 1e-5) << n;
      EXPECT_NEAR(PathLength(d, open, false), BruteForce(d, false), 1e-5) << n;
    }
  }
}

TEST(GaitOrder, PointsOnALineComeInOrder) {
  // Gaits at positions 0, 3, 1, 2 on a line: the open path walks the line.
  std::vector<Eigen::MatrixXd> gaits;
  for (double position : {0.0, 3.0, 1.0, 2.0}) gaits.push_back(Eigen::MatrixXd::Constant(2, 2, position));
  const Eigen::MatrixXd d = GaitDistances(gaits);
  EXPECT_DOUBLE_EQ(d(0, 1), 3.0);
  std::vector<int> open = ShortestOpenPath(d);
  if (open.front() != 0) std::reverse(open.begin(), open.end());
  EXPECT_EQ(open, (std::vector<int>{0, 2, 3, 1}));
}

TEST(GaitOrder, LargeInstancesUseTheHeuristicAndStayValid) {
  // Points on a circle: the shortest tour is the circle itself.
  const int n = 30;
  Eigen::MatrixXd points(n, 2);
  std::vector<int> shuffled(n);
  std::iota(shuffled.begin(), shuffled.end(), 0);
  std::mt19937 random(3);  // (std::random_shuffle is gone from C++17)
  std::shuffle(shuffled.begin(), shuffled.end(), random);
  for (int i = 0; i < n; ++i) {
    const double a = 2 * std::numbers::pi * shuffled[i] / n;
    points.row(i) << std::cos(a), std::sin(a);
  }
  Eigen::MatrixXd d(n, n);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) d(i, j) = (points.row(i) - points.row(j)).norm();
  }
  const std::vector<int> tour = ShortestClosedPath(d);
  ASSERT_TRUE(IsPermutation(tour, n));
  EXPECT_NEAR(PathLength(d, tour, true), n * 2 * std::sin(std::numbers::pi / n), 1e-9);
}

}  // namespace
}  // namespace jgpm
