#include "prior/numerics/cholesky.h"

#include <algorithm>
#include <cmath>
#include <random>

#include <Eigen/Cholesky>
#include <gtest/gtest.h>

#include "prior/numerics/kernel.h"

namespace jgpm {
namespace {

Eigen::MatrixXd RandomSpd(int n, unsigned seed) {
  std::srand(seed);
  const Eigen::MatrixXd a = Eigen::MatrixXd::Random(n, n);
  return a * a.transpose() + n * Eigen::MatrixXd::Identity(n, n);
}

// Oracle: Eigen's own LLT.
TEST(Cholesky, MatchesEigen) {
  for (int n : {1, 5, 64, 300}) {
    const Eigen::MatrixXd k = RandomSpd(n, n);
    Cholesky chol;
    ASSERT_TRUE(chol.Compute(k)) << chol.why();
    EXPECT_EQ(chol.jitter(), 0.0);
    const Eigen::LLT<Eigen::MatrixXd> llt(k);
    const Eigen::MatrixXd b = Eigen::MatrixXd::Random(n, 3);
    EXPECT_LT((chol.Solve(b) - llt.solve(b)).norm(), 1e-9 * b.norm());
    EXPECT_NEAR(chol.LogDeterminant(), 2 * llt.matrixL().toDenseMatrix().diagonal().array().log().sum(), 1e-8 * n);
    EXPECT_LT((k * chol.Inverse() - Eigen::MatrixXd::Identity(n, n)).norm(), 1e-9 * n);
    // Half solves, for a matrix and for a vector: L x = b and L^T x = b with L from LLT.
    const Eigen::MatrixXd l = llt.matrixL().toDenseMatrix();
    const Eigen::VectorXd v = Eigen::VectorXd::Random(n);
    EXPECT_LT((l * chol.HalfSolve(b) - b).norm(), 1e-9 * b.norm());
    EXPECT_LT((l * chol.HalfSolve(v) - v).norm(), 1e-9 * v.norm());
    EXPECT_LT((l.transpose() * chol.HalfSolveTransposed(b) - b).norm(), 1e-9 * b.norm());
    EXPECT_LT((l.transpose() * chol.HalfSolveTransposed(v) - v).norm(), 1e-9 * v.norm());
  }
}

TEST(Cholesky, DuplicatePointsNeedJitterWhichIsReported) {
  // An RBF kernel without noise on two identical points is singular.
  Eigen::MatrixXd k(3, 3);
  k << 1, 1, 0.5, 1, 1, 0.5, 0.5, 0.5, 1;
  Cholesky chol;
  ASSERT_TRUE(chol.Compute(k)) << chol.why();
  EXPECT_GT(chol.jitter(), 0.0);
  EXPECT_LT(chol.jitter(), 1e-2);
  EXPECT_TRUE(std::isfinite(chol.LogDeterminant()));
  EXPECT_TRUE(chol.Solve(Eigen::MatrixXd::Ones(3, 1)).allFinite());
}

TEST(Cholesky, RefusesNanAndIndefinite) {
  Eigen::MatrixXd k = Eigen::MatrixXd::Identity(3, 3);
  k(1, 1) = std::nan("");
  Cholesky chol;
  EXPECT_FALSE(chol.Compute(k));
  EXPECT_NE(chol.why().find("NaN"), std::string::npos);
  k = -Eigen::MatrixXd::Identity(3, 3);
  EXPECT_FALSE(chol.Compute(k));
  k = Eigen::MatrixXd::Identity(3, 3);
  k(0, 0) = -0.5;  // a clearly negative eigenvalue: jitter up to 1% of the mean cannot fix it
  EXPECT_FALSE(chol.Compute(k));
  EXPECT_NE(chol.why().find("not positive definite"), std::string::npos) << chol.why();
}

// Factorising in K's own storage gives what the copying path gives, bit for bit, also
// when jitter must be retried (each retry restores K from its upper triangle) and when it
// refuses.
TEST(Cholesky, InPlaceIsTheCopyingPath) {
  // 40 points on 10 sites (each 4 times), RBF with noise e^-40: nearly singular. And a
  // matrix with an eigenvalue of -1e-8 (mean diagonal 1/6): jitter 1.7e-10 and 1.7e-9 fail,
  // 1.7e-8 holds, so K is restored twice.
  Eigen::MatrixXd x(40, 3);
  for (int i = 0; i < 40; ++i) x.row(i) = Eigen::Vector3d(i % 10, 0.5 * (i % 10), 0.0) * 0.3;
  const Kernel rbf(Kernel::Kind::kRbf, Eigen::Vector3d(0.0, 0.0, 40.0));
  const Eigen::MatrixXd negative = Eigen::MatrixXd::Constant(6, 6, 1.0 / 6) - 1e-8 * Eigen::MatrixXd::Identity(6, 6);
  Eigen::MatrixXd indefinite = Eigen::MatrixXd::Identity(3, 3);
  indefinite(0, 0) = -0.5;
  Eigen::MatrixXd with_nan = Eigen::MatrixXd::Identity(3, 3);
  with_nan(2, 2) = std::nan("");
  const Eigen::MatrixXd spd = RandomSpd(64, 7);
  for (const Eigen::MatrixXd& k : {spd, rbf.Matrix(x), negative, indefinite, with_nan}) {
    Cholesky copying, in_place;
    const bool ok = copying.Compute(k);
    EXPECT_EQ(in_place.Compute(Eigen::MatrixXd(k)), ok);
    EXPECT_EQ(in_place.why(), copying.why());
    EXPECT_EQ(in_place.jitter(), copying.jitter());
    if (!ok) continue;
    const Eigen::MatrixXd b = Eigen::MatrixXd::Random(k.rows(), 2);
    EXPECT_EQ(in_place.Solve(b), copying.Solve(b));
    EXPECT_EQ(in_place.LogDeterminant(), copying.LogDeterminant());
  }
  Cholesky chol;
  ASSERT_TRUE(chol.Compute(Eigen::MatrixXd(negative)));
  EXPECT_GT(chol.jitter(), 1e-8 / 6);  // the retries were exercised: past the first two jitters
}

// The oracle: greedy selection written out, each step's residual diagonal
// K_ii - K_iS K_SS^-1 K_Si from a fresh solve against the chosen rows.
std::vector<int> BruteForceGreedy(const Eigen::MatrixXd& k, int count) {
  std::vector<int> chosen;
  for (int step = 0; step < count; ++step) {
    Eigen::MatrixXd kss(chosen.size(), chosen.size()), ksn(chosen.size(), k.rows());
    for (size_t a = 0; a < chosen.size(); ++a) {
      ksn.row(a) = k.row(chosen[a]);
      for (size_t b = 0; b < chosen.size(); ++b) kss(a, b) = k(chosen[a], chosen[b]);
    }
    Eigen::VectorXd residual = k.diagonal();
    if (!chosen.empty()) residual -= (ksn.cwiseProduct(kss.ldlt().solve(ksn))).colwise().sum().transpose();
    Eigen::Index best;
    residual.maxCoeff(&best);
    chosen.push_back(static_cast<int>(best));
  }
  return chosen;
}

TEST(GreedyPivotOrder, IsTheGreedySelection) {
  // 200 random points (past LAPACK's block size, so the blocked path runs), an RBF kernel
  // wide enough that later choices depend on earlier ones.
  std::mt19937 random(5);
  std::uniform_real_distribution<double> uniform(-2, 2);
  Eigen::MatrixXd x(200, 3);
  for (int i = 0; i < x.rows(); ++i) x.row(i) << uniform(random), uniform(random), uniform(random);
  const Kernel kernel(Kernel::Kind::kRbf, Eigen::Vector3d(0, 0, std::log(100.0)));
  const Eigen::MatrixXd k = kernel.CrossMatrix(x, x, kernel.RbfCross(x, x));
  const std::vector<int> order = GreedyPivotOrder(k);
  ASSERT_EQ(order.size(), 200u);
  std::vector<int> sorted = order;
  std::sort(sorted.begin(), sorted.end());
  for (int i = 0; i < 200; ++i) EXPECT_EQ(sorted[i], i);  // a permutation
  const std::vector<int> expected = BruteForceGreedy(k, 80);
  EXPECT_EQ(std::vector<int>(order.begin(), order.begin() + 80), expected);
}

}  // namespace
}  // namespace jgpm
