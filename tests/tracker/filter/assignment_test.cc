// The assignment against brute force: every pairing of rows with columns tried.
#include "tracker/filter/assignment.h"

#include <algorithm>
#include <limits>
#include <numeric>
#include <random>
#include <stdexcept>

#include <gtest/gtest.h>

namespace jgpm {
namespace {

// The least total cost over all pairings that pair min(rows, columns) rows.
double BruteForce(const Eigen::MatrixXd& cost) {
  const bool wide = cost.rows() <= cost.cols();
  const Eigen::MatrixXd a = wide ? cost : Eigen::MatrixXd(cost.transpose());
  std::vector<int> columns(a.cols());
  std::iota(columns.begin(), columns.end(), 0);
  double best = std::numeric_limits<double>::infinity();
  do {  // the first rows() columns of each permutation
    double sum = 0;
    for (int i = 0; i < a.rows(); ++i) sum += a(i, columns[i]);
    best = std::min(best, sum);
  } while (std::next_permutation(columns.begin(), columns.end()));
  return best;
}

TEST(MinCostAssignment, MatchesBruteForceOnRandomMatrices) {
  std::mt19937 rng(5);
  std::uniform_int_distribution<int> size(1, 6);
  std::uniform_real_distribution<double> value(0, 10);
  for (int trial = 0; trial < 300; ++trial) {
    Eigen::MatrixXd cost(size(rng), size(rng));
    for (int i = 0; i < cost.rows(); ++i)
      for (int j = 0; j < cost.cols(); ++j) cost(i, j) = trial % 3 == 0 ? std::floor(value(rng) / 3) : value(rng);
    const std::vector<int> column = MinCostAssignment(cost, std::numeric_limits<double>::infinity());
    ASSERT_EQ(column.size(), static_cast<size_t>(cost.rows()));
    double sum = 0;
    int paired = 0;
    std::vector<bool> taken(cost.cols(), false);
    for (int i = 0; i < cost.rows(); ++i) {
      if (column[i] < 0) continue;
      ASSERT_LT(column[i], cost.cols());
      ASSERT_FALSE(taken[column[i]]) << "column " << column[i] << " paired twice";
      taken[column[i]] = true;
      sum += cost(i, column[i]);
      ++paired;
    }
    EXPECT_EQ(paired, std::min(cost.rows(), cost.cols()));
    EXPECT_NEAR(sum, BruteForce(cost), 1e-9) << cost;
  }
}

TEST(MinCostAssignment, CutsPairsAboveTheLimitAndRefusesNaN) {
  Eigen::MatrixXd cost(2, 3);
  cost << 1, 9, 9,
          9, 9, 7;
  EXPECT_EQ(MinCostAssignment(cost, 8), (std::vector<int>{0, 2}));
  EXPECT_EQ(MinCostAssignment(cost, 5), (std::vector<int>{0, -1}));
  EXPECT_EQ(MinCostAssignment(Eigen::MatrixXd(0, 3), 1).size(), 0u);
  EXPECT_EQ(MinCostAssignment(Eigen::MatrixXd(2, 0), 1), (std::vector<int>{-1, -1}));
  cost(1, 1) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(MinCostAssignment(cost, 8), std::invalid_argument);
}

}  // namespace
}  // namespace jgpm
