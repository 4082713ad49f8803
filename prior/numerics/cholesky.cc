#include "prior/numerics/cholesky.h"

#include <cmath>
#include <utility>

#include <lapacke.h>

#include "io/base/error.h"

namespace jgpm {

bool Cholesky::Compute(const Eigen::MatrixXd& k, double max_relative_jitter) {
  return Factorise(k, max_relative_jitter, [this, &k](double jitter) {
    factor_ = k;
    factor_.diagonal().array() += jitter;
  });
}

bool Cholesky::Compute(Eigen::MatrixXd&& k, double max_relative_jitter) {
  factor_ = std::move(k);
  const Eigen::VectorXd diagonal = factor_.diagonal();
  return Factorise(factor_, max_relative_jitter, [this, &diagonal](double jitter) {
    if (jitter == 0) return;  // the first try: factor_ is K as given
    // dpotrf wrote the lower triangle and the diagonal only: K comes back from the upper
    // triangle and the diagonal kept above.
    for (Eigen::Index j = 0; j < factor_.cols(); ++j)
      for (Eigen::Index i = j + 1; i < factor_.rows(); ++i) factor_(i, j) = factor_(j, i);
    factor_.diagonal() = diagonal.array() + jitter;
  });
}

bool Cholesky::Factorise(const Eigen::MatrixXd& k, double max_relative_jitter,
                         const std::function<void(double)>& load) {
  JGPM_CHECK(k.rows() == k.cols());
  ok_ = false;
  jitter_ = 0;
  const int n = static_cast<int>(k.rows());
  if (!k.allFinite()) {
    why_ = "kernel matrix holds NaN or inf";
    return false;
  }
  const double mean_diagonal = n > 0 ? k.diagonal().mean() : 1.0;
  if (!(mean_diagonal > 0)) {
    why_ = "kernel matrix has a non-positive mean diagonal";
    return false;
  }
  const double max_jitter = max_relative_jitter * mean_diagonal;
  for (double jitter = 0; jitter <= max_jitter; jitter = jitter == 0 ? 1e-9 * mean_diagonal : jitter * 10) {
    load(jitter);  // `k` may be factor_ itself: read before the first load only
    if (n == 0 || LAPACKE_dpotrf(LAPACK_COL_MAJOR, 'L', n, factor_.data(), n) == 0) {
      jitter_ = jitter;
      ok_ = true;
      why_.clear();
      return true;
    }
  }
  why_ = "kernel matrix not positive definite even with jitter " + std::to_string(max_jitter);
  return false;
}

double Cholesky::LogDeterminant() const {
  JGPM_CHECK(ok_);
  return 2.0 * factor_.diagonal().array().log().sum();
}

Eigen::MatrixXd Cholesky::Solve(const Eigen::MatrixXd& b) const {
  JGPM_CHECK(ok_ && b.rows() == factor_.rows());
  Eigen::MatrixXd x = b;
  const int n = size();
  if (n > 0 && b.cols() > 0) {
    const int info = LAPACKE_dpotrs(LAPACK_COL_MAJOR, 'L', n, static_cast<int>(b.cols()),
                                    factor_.data(), n, x.data(), n);
    JGPM_CHECK(info == 0);
  }
  return x;
}

Eigen::MatrixXd Cholesky::HalfSolve(const Eigen::MatrixXd& b) const {
  JGPM_CHECK(ok_ && b.rows() == factor_.rows());
  return factor_.triangularView<Eigen::Lower>().solve(b);
}

Eigen::VectorXd Cholesky::HalfSolve(const Eigen::VectorXd& b) const {
  JGPM_CHECK(ok_ && b.rows() == factor_.rows());
  Eigen::VectorXd x = b;
  factor_.triangularView<Eigen::Lower>().solveInPlace(x);
  return x;
}

void Cholesky::HalfSolveInPlace(Eigen::Ref<Eigen::MatrixXd> b) const {
  JGPM_CHECK(ok_ && b.rows() == factor_.rows());
  factor_.triangularView<Eigen::Lower>().solveInPlace(b);
}

Eigen::MatrixXd Cholesky::HalfSolveTransposed(const Eigen::MatrixXd& b) const {
  JGPM_CHECK(ok_ && b.rows() == factor_.rows());
  return factor_.triangularView<Eigen::Lower>().transpose().solve(b);
}

Eigen::VectorXd Cholesky::HalfSolveTransposed(const Eigen::VectorXd& b) const {
  JGPM_CHECK(ok_ && b.rows() == factor_.rows());
  Eigen::VectorXd x = b;
  factor_.triangularView<Eigen::Lower>().transpose().solveInPlace(x);
  return x;
}

Eigen::MatrixXd Cholesky::Inverse() const {
  JGPM_CHECK(ok_);
  Eigen::MatrixXd inverse = factor_;
  const int n = size();
  if (n > 0) {
    const int info = LAPACKE_dpotri(LAPACK_COL_MAJOR, 'L', n, inverse.data(), n);
    JGPM_CHECK(info == 0);
  }
  // dpotri fills the lower triangle; mirror it.
  inverse.triangularView<Eigen::StrictlyUpper>() = inverse.transpose();
  return inverse;
}

namespace {
// Callers check for NaN/inf before factorising; LAPACKE's own full-matrix scans would only
// repeat that on every call.
const bool kNanCheckOff = [] {
  LAPACKE_set_nancheck(0);
  return true;
}();
}  // namespace

std::vector<int> GreedyPivotOrder(const Eigen::MatrixXd& k) {
  JGPM_CHECK(k.rows() == k.cols());
  const int n = static_cast<int>(k.rows());
  Eigen::MatrixXd factor = k;
  std::vector<lapack_int> pivots(n);
  lapack_int rank = 0;
  // info > 0 only says K is rank-deficient (expected: a smooth kernel over many points);
  // the pivots are still the greedy order up to the rank.
  const lapack_int info = LAPACKE_dpstrf(LAPACK_COL_MAJOR, 'L', n, factor.data(), n, pivots.data(), &rank, -1.0);
  JGPM_CHECK(info >= 0);
  std::vector<int> order(n);
  for (int j = 0; j < n; ++j) order[j] = static_cast<int>(pivots[j]) - 1;  // LAPACK counts from 1
  return order;
}

}  // namespace jgpm
