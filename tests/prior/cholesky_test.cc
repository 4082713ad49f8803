#include "prior/cholesky.h"

#include <Eigen/Cholesky>
#include <gtest/gtest.h>

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

}  // namespace
}  // namespace jgpm
