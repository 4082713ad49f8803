// The kernel density against brute force: the width is the median distance to the k-th
// nearest other point (found by sorting all distances), the density the plain mean of the
// Gaussian kernels, the gradient its finite difference.
#include "prior/model/latent_density.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include <gtest/gtest.h>

namespace jgpm {
namespace {

Eigen::MatrixXd Points(int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal;
  Eigen::MatrixXd p(n, 3);
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < 3; ++k) p(i, k) = normal(rng) * (k + 1);
  return p;
}

double BruteWidth(const Eigen::MatrixXd& p, int k) {
  const int n = static_cast<int>(p.rows());
  std::vector<double> kth;
  for (int i = 0; i < n; ++i) {
    std::vector<double> d;
    for (int j = 0; j < n; ++j) d.push_back((p.row(i) - p.row(j)).norm());
    std::sort(d.begin(), d.end());  // d[0] is the point itself
    kth.push_back(d[k]);
  }
  std::sort(kth.begin(), kth.end());
  return kth[n / 2];
}

double BruteLogDensity(const Eigen::MatrixXd& p, double h, const Eigen::Vector3d& x) {
  double sum = 0;
  for (int i = 0; i < p.rows(); ++i)
    sum += std::exp(-(p.row(i).transpose() - x).squaredNorm() / (2 * h * h)) / std::pow(2 * std::numbers::pi * h * h, 1.5);
  return std::log(sum / p.rows());
}

TEST(LatentDensity, MatchesBruteForceForEveryNeighbourCount) {
  const Eigen::MatrixXd p = Points(101, 3);
  std::mt19937 rng(4);
  std::normal_distribution<double> normal;
  for (const int k : {1, 2, 8}) {
    const LatentDensity density(p, k);
    const double h = BruteWidth(p, k);
    EXPECT_NEAR(density.width(), h, 1e-12) << k;
    for (int trial = 0; trial < 20; ++trial) {
      const Eigen::Vector3d x(normal(rng), 2 * normal(rng), 3 * normal(rng));
      Eigen::Vector3d gradient;
      EXPECT_NEAR(density.LogDensity(x, &gradient), BruteLogDensity(p, h, x), 1e-9) << k;
      Eigen::VectorXd scratch(p.rows());
      EXPECT_NEAR(density.LogDensity(x, scratch), BruteLogDensity(p, h, x), 1e-9) << k;
      for (int d = 0; d < 3; ++d) {
        Eigen::Vector3d step = Eigen::Vector3d::Zero();
        step[d] = 1e-6;
        const double numeric = (BruteLogDensity(p, h, x + step) - BruteLogDensity(p, h, x - step)) / 2e-6;
        EXPECT_NEAR(gradient[d], numeric, 1e-5 * std::max(1.0, std::abs(numeric))) << k << " " << d;
      }
    }
  }
  // A wider neighbourhood gives a wider kernel.
  EXPECT_LT(LatentDensity(p, 1).width(), LatentDensity(p, 8).width());
}

}  // namespace
}  // namespace jgpm
