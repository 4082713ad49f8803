#include "prior/numerics/kernel.h"

#include <gtest/gtest.h>

namespace jgpm {
namespace {

// L = sum_ij G_ij K_ij for a fixed random symmetric G: dL/dK = G, so AddGradient must give
// dL/dX and dL/dlog-params; compared with central finite differences.
double Contract(const Kernel& kernel, const Eigen::MatrixXd& x, const Eigen::MatrixXd& g) {
  return kernel.Matrix(x).cwiseProduct(g).sum();
}

void CheckGradient(Kernel::Kind kind, const Eigen::VectorXd& log_params) {
  std::srand(11);
  const int n = 7;
  const Eigen::MatrixXd x = Eigen::MatrixXd::Random(n, 3);
  Eigen::MatrixXd g = Eigen::MatrixXd::Random(n, n);
  g = (g + g.transpose()).eval();
  const Kernel kernel(kind, log_params);
  Eigen::MatrixXd dx = Eigen::MatrixXd::Zero(n, 3);
  Eigen::VectorXd dp = Eigen::VectorXd::Zero(kernel.NumParams());
  kernel.AddGradient(x, g, kernel.RbfPart(x), &dx, &dp);
  const double h = 1e-6;
  for (int i = 0; i < n; ++i) {
    for (int d = 0; d < 3; ++d) {
      Eigen::MatrixXd plus = x, minus = x;
      plus(i, d) += h;
      minus(i, d) -= h;
      const double fd = (Contract(kernel, plus, g) - Contract(kernel, minus, g)) / (2 * h);
      EXPECT_NEAR(dx(i, d), fd, 1e-6 * std::max(1.0, std::abs(fd))) << i << "," << d;
    }
  }
  for (int k = 0; k < kernel.NumParams(); ++k) {
    Eigen::VectorXd plus = log_params, minus = log_params;
    plus[k] += h;
    minus[k] -= h;
    const double fd = (Contract(Kernel(kind, plus), x, g) - Contract(Kernel(kind, minus), x, g)) / (2 * h);
    EXPECT_NEAR(dp[k], fd, 1e-6 * std::max(1.0, std::abs(fd))) << "param " << k;
  }
}

TEST(Kernel, RbfGradientMatchesFiniteDifferences) {
  CheckGradient(Kernel::Kind::kRbf, Eigen::Vector3d(0.3, -0.5, 2.0));
}

TEST(Kernel, RbfLinearGradientMatchesFiniteDifferences) {
  CheckGradient(Kernel::Kind::kRbfLinear, Eigen::Vector4d(-0.2, 0.4, -1.0, 3.0));
}

// The linear kernel (a test oracle, see ObjectiveTerms::linear_mapping): b2 is unused, so
// its derivative is zero and finite differences see the same.
TEST(Kernel, LinearGradientMatchesFiniteDifferences) {
  CheckGradient(Kernel::Kind::kLinear, Eigen::Vector3d(0.4, -0.3, 1.5));
}

TEST(Kernel, ValuesByHand) {
  const Kernel rbf(Kernel::Kind::kRbf, Eigen::Vector3d(std::log(2.0), std::log(0.5), std::log(100.0)));
  Eigen::MatrixXd x(2, 3);
  x << 0, 0, 0, 1, 2, 2;  // |x0 - x1|^2 = 9
  const Eigen::MatrixXd k = rbf.Matrix(x);
  EXPECT_NEAR(k(0, 0), 2.0 + 0.01, 1e-12);
  EXPECT_NEAR(k(0, 1), 2.0 * std::exp(-0.25 * 9), 1e-12);
  EXPECT_NEAR(rbf.Cross(x, Eigen::Vector3d(1, 2, 2))[0], 2.0 * std::exp(-0.25 * 9), 1e-12);
  EXPECT_NEAR(rbf.Self(Eigen::Vector3d(5, 5, 5)), 2.0, 1e-12);
  const Kernel lin(Kernel::Kind::kRbfLinear, Eigen::Vector4d(0, 0, std::log(3.0), std::log(10.0)));
  EXPECT_NEAR(lin.Matrix(x)(1, 1), 1.0 + 3.0 * 9 + 0.1, 1e-12);
  EXPECT_NEAR(lin.Cross(x, Eigen::Vector3d(1, 0, 0))[1], std::exp(-0.5 * 8) + 3.0, 1e-12);
  // k(x, x') = b1 x . x' + delta / b3, whatever b2.
  const Kernel linear(Kernel::Kind::kLinear, Eigen::Vector3d(std::log(2.0), std::log(7.0), std::log(10.0)));
  EXPECT_NEAR(linear.Matrix(x)(0, 0), 0.1, 1e-12);
  EXPECT_NEAR(linear.Matrix(x)(1, 1), 2.0 * 9 + 0.1, 1e-12);
  EXPECT_NEAR(linear.Matrix(x)(0, 1), 0.0, 1e-12);
  EXPECT_NEAR(linear.Cross(x, Eigen::Vector3d(1, -1, 3))[1], 2.0 * (1 - 2 + 6), 1e-12);
  EXPECT_NEAR(linear.Self(Eigen::Vector3d(1, -1, 3)), 2.0 * 11, 1e-12);
}

}  // namespace
}  // namespace jgpm
