#include "prior/numerics/rbf_row.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

namespace jgpm {
namespace {

// Scalar oracle: the kernel as written in METHOD.md.
double Oracle(const std::vector<double>& x, int n, int i, const double* q, double b1, double b2) {
  double d2 = 0.0;
  for (int d = 0; d < 3; ++d) d2 += (x[d * n + i] - q[d]) * (x[d * n + i] - q[d]);
  return b1 * std::exp(-0.5 * b2 * d2);
}

// Lengths that are and are not multiples of the SIMD width (2, 4 or 8 doubles), so the
// vector body and its remainder loop are both exercised.
TEST(RbfRow, MatchesScalarKernelForAnyLength) {
  std::mt19937 rng(3);
  std::normal_distribution<double> normal(0.0, 1.5);
  for (const int n : {1, 2, 3, 7, 8, 9, 15, 16, 17, 1801}) {
    std::vector<double> x(3 * n);
    for (double& v : x) v = normal(rng);
    const double q[3] = {normal(rng), normal(rng), normal(rng)};
    std::vector<double> out(n, -1.0);
    RbfRow(x.data(), n, q, 1.7, 0.8, out.data());
    for (int i = 0; i < n; ++i) {
      const double expected = Oracle(x, n, i, q, 1.7, 0.8);
      EXPECT_NEAR(out[i], expected, 1e-13 * expected + 1e-300) << "n=" << n << " i=" << i;
    }
  }
}

TEST(RbfRow, EmptyRowWritesNothing) {
  const double q[3] = {0, 0, 0};
  double sentinel = 42.0;
  RbfRow(nullptr, 0, q, 1.0, 1.0, &sentinel);
  EXPECT_EQ(sentinel, 42.0);
}

// A point on itself gives the signal variance; far points underflow to zero, never NaN
// (fast-math must not turn exp(-large) into garbage).
TEST(RbfRow, SelfIsSignalVarianceAndFarPointsVanish) {
  const int n = 9;
  std::vector<double> x(3 * n, 0.0);
  for (int i = 1; i < n; ++i) x[i] = std::pow(10.0, i - 1);  // 1 .. 1e7 along the first axis
  const double q[3] = {0, 0, 0};
  std::vector<double> out(n);
  RbfRow(x.data(), n, q, 2.5, 1.0, out.data());
  EXPECT_DOUBLE_EQ(out[0], 2.5);
  EXPECT_NEAR(out[1], 2.5 * std::exp(-0.5), 1e-14);
  for (int i = 3; i < n; ++i) {
    EXPECT_TRUE(std::isfinite(out[i]));
    EXPECT_GE(out[i], 0.0);
    EXPECT_LT(out[i], 1e-20);
  }
}

}  // namespace
}  // namespace jgpm
