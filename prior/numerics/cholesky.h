// Cholesky factorisation of kernel matrices with adaptive jitter, on LAPACK (OpenBLAS).
//
// When K is not numerically positive definite (duplicate latent points, a vanishing noise
// term), jitter is added to its diagonal: first 1e-9 times the mean diagonal, then ten
// times more each try, up to max_relative_jitter. The jitter used is reported so training
// summaries can show it. Never forms an inverse to solve a system; Inverse() exists only
// because the gradient of ln|K| needs every entry of K^-1.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace jgpm {

class Cholesky {
 public:
  // Factorises K (only its lower triangle is read). False when K holds NaN/inf or no
  // jitter up to max_relative_jitter * mean(diag K) makes it positive definite; why() says
  // which.
  bool Compute(const Eigen::MatrixXd& k, double max_relative_jitter = 1e-2);
  // The same in K's own storage, without a copy (for N = 1800, 26 MB fresh, 60 ms of page
  // faults on our machines). K must be symmetric, both triangles: a retry with jitter
  // restores its lower triangle from the upper one.
  bool Compute(Eigen::MatrixXd&& k, double max_relative_jitter = 1e-2);

  bool ok() const { return ok_; }
  const std::string& why() const { return why_; }
  // Jitter added to the diagonal (0 when K factorised as it was).
  double jitter() const { return jitter_; }
  int size() const { return static_cast<int>(factor_.rows()); }

  // ln |K + jitter I|.
  double LogDeterminant() const;
  // (K + jitter I)^-1 b.
  Eigen::MatrixXd Solve(const Eigen::MatrixXd& b) const;
  // L^-1 b, where K + jitter I = L L^T: |L^-1 k|^2 = k^T K^-1 k without the cancellation
  // of a quadratic form in an explicit inverse.
  Eigen::MatrixXd HalfSolve(const Eigen::MatrixXd& b) const;
  // The same for one vector: a plain triangular solve (the matrix form repacks the whole
  // factor for a single column, ~1.5 ms for N = 1800).
  Eigen::VectorXd HalfSolve(const Eigen::VectorXd& b) const;
  // b <- L^-1 b, in place (no allocation for the caller's workspace).
  void HalfSolveInPlace(Eigen::Ref<Eigen::MatrixXd> b) const;
  // L^-T b.
  Eigen::MatrixXd HalfSolveTransposed(const Eigen::MatrixXd& b) const;
  Eigen::VectorXd HalfSolveTransposed(const Eigen::VectorXd& b) const;
  // (K + jitter I)^-1 as a full symmetric matrix, from the factor (LAPACK dpotri).
  Eigen::MatrixXd Inverse() const;

 private:
  // The checks and the jitter loop; `load(jitter)` puts K + jitter I into factor_.
  bool Factorise(const Eigen::MatrixXd& k, double max_relative_jitter, const std::function<void(double)>& load);

  Eigen::MatrixXd factor_;  // lower triangle holds L
  double jitter_ = 0;
  bool ok_ = false;
  std::string why_;
};

// Row order of greedy pivoted Cholesky of the symmetric positive semi-definite `k` (only
// its lower triangle is read): row order[j] has the largest diagonal of the residual
// K - K_:S K_SS^-1 K_S: after the rows S = order[0..j-1]. All rows, each once; past the
// numerical rank the order is the factorisation's.
std::vector<int> GreedyPivotOrder(const Eigen::MatrixXd& k);

}  // namespace jgpm
