// Covariance functions of the Gaussian-process models (METHOD.md section 1), with analytic
// gradients with respect to the latent points and the log hyper-parameters.
//
//   mapping  (kRbf):       k(x, x') = b1 exp(-b2/2 |x - x'|^2)                 + delta / b3
//   dynamics (kRbfLinear): k(x, x') = a1 exp(-a2/2 |x - x'|^2) + a3 x . x'     + delta / a4
//   kLinear:               k(x, x') = b1 x . x'                                + delta / b3
//
// kLinear (b2 unused) is the mapping only under ObjectiveTerms::linear_mapping, a test
// oracle: its MAP latent points are PCA's in closed form.
//
// Hyper-parameters are kept as logarithms, so optimisers see an unconstrained problem.
#pragma once

#include <Eigen/Core>

namespace jgpm {

class Kernel {
 public:
  enum class Kind { kRbf, kRbfLinear, kLinear };

  // `log_params` has 4 entries (kRbfLinear) or 3, in the order above.
  Kernel(Kind kind, const Eigen::VectorXd& log_params);

  Kind kind() const { return kind_; }
  int NumParams() const { return kind_ == Kind::kRbfLinear ? 4 : 3; }
  const Eigen::VectorXd& log_params() const { return log_params_; }
  // The RBF part's b1 (a1); 0 for kLinear.
  double signal_variance() const { return kind_ == Kind::kLinear ? 0.0 : p_[0]; }
  double inverse_width() const { return p_[1]; }
  // The linear part's a3 (kLinear: b1); 0 for kRbf.
  double linear_variance() const { return kind_ == Kind::kRbf ? 0.0 : p_[LinearIndex()]; }
  // The noise variance on the diagonal: 1 / b3 (or 1 / a4).
  double noise_variance() const { return 1.0 / p_[NumParams() - 1]; }

  // The RBF part b1 exp(-b2/2 |x_i - x_j|^2) of K(X) (zero for kLinear): computed once,
  // shared by Matrix and AddGradient (its N^2 exponentials are a large part of an
  // evaluation).
  Eigen::MatrixXd RbfPart(const Eigen::MatrixXd& x) const;
  // K(X) for the rows of X, noise included on the diagonal; `rbf` is RbfPart(x), taken by
  // value so that a temporary becomes K without a copy (26 MB fresh for N = 1800).
  Eigen::MatrixXd Matrix(const Eigen::MatrixXd& x, Eigen::MatrixXd rbf) const;
  Eigen::MatrixXd Matrix(const Eigen::MatrixXd& x) const { return Matrix(x, RbfPart(x)); }
  // k(x_i, x*) for every row x_i of X (no noise: x* is a new point).
  Eigen::VectorXd Cross(const Eigen::MatrixXd& x, const Eigen::Vector3d& x_star) const;
  // k(x*, x*) without noise.
  double Self(const Eigen::Vector3d& x_star) const;

  // The RBF part of K(A, B) (|A| x |B|, zero for kLinear), and the whole of it without
  // noise (A and B are different points, or inducing inputs).
  Eigen::MatrixXd RbfCross(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) const;
  Eigen::MatrixXd CrossMatrix(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b, const Eigen::MatrixXd& rbf) const;
  // Chain rule through C = CrossMatrix(a, b, rbf): given G = dL/dC (|A| x |B|, entries
  // taken as independent; for K(A, A) pass A twice and both gradients land in the same
  // matrix), adds dL/dA to `da`, dL/dB to `db` and dL/d(log params) to `dlog_params`.
  void AddCrossGradient(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b, const Eigen::MatrixXd& g,
                        const Eigen::MatrixXd& rbf, Eigen::MatrixXd* da, Eigen::MatrixXd* db,
                        Eigen::VectorXd* dlog_params) const;
  // sum_i k(x_i, x_i) without noise, and its gradient (added to `dx`, `dlog_params`,
  // times `weight`).
  double SelfSum(const Eigen::MatrixXd& x) const;
  void AddSelfSumGradient(const Eigen::MatrixXd& x, double weight, Eigen::MatrixXd* dx,
                          Eigen::VectorXd* dlog_params) const;

  // Chain rule through K: given G = dL/dK (symmetric, for K = Matrix(x)) and
  // rbf = RbfPart(x), adds dL/dX to `dx` and dL/d(log params) to `dlog_params`.
  void AddGradient(const Eigen::MatrixXd& x, const Eigen::MatrixXd& g, const Eigen::MatrixXd& rbf,
                   Eigen::MatrixXd* dx, Eigen::VectorXd* dlog_params) const;

 private:
  // Index of the linear part's variance in the parameters (not kRbf).
  int LinearIndex() const { return kind_ == Kind::kLinear ? 0 : 2; }

  Kind kind_;
  Eigen::VectorXd log_params_;
  Eigen::VectorXd p_;  // exp(log_params_)
};

}  // namespace jgpm
