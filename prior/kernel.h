// Covariance functions of the Gaussian-process models (METHOD.md section 1), with analytic
// gradients with respect to the latent points and the log hyper-parameters.
//
//   mapping  (kRbf):       k(x, x') = b1 exp(-b2/2 |x - x'|^2)                 + delta / b3
//   dynamics (kRbfLinear): k(x, x') = a1 exp(-a2/2 |x - x'|^2) + a3 x . x'     + delta / a4
//
// Hyper-parameters are kept as logarithms, so optimisers see an unconstrained problem.
#pragma once

#include <Eigen/Core>

namespace jgpm {

class Kernel {
 public:
  enum class Kind { kRbf, kRbfLinear };

  // `log_params` has 3 entries (kRbf) or 4 (kRbfLinear), in the order above.
  Kernel(Kind kind, const Eigen::VectorXd& log_params);

  Kind kind() const { return kind_; }
  int NumParams() const { return kind_ == Kind::kRbf ? 3 : 4; }
  const Eigen::VectorXd& log_params() const { return log_params_; }
  double signal_variance() const { return p_[0]; }
  double inverse_width() const { return p_[1]; }
  double linear_variance() const { return kind_ == Kind::kRbf ? 0.0 : p_[2]; }
  // The noise variance on the diagonal: 1 / b3 (or 1 / a4).
  double noise_variance() const { return 1.0 / p_[NumParams() - 1]; }

  // The RBF part b1 exp(-b2/2 |x_i - x_j|^2) of K(X): computed once, shared by Matrix
  // and AddGradient (its N^2 exponentials are a large part of an evaluation).
  Eigen::MatrixXd RbfPart(const Eigen::MatrixXd& x) const;
  // K(X) for the rows of X, noise included on the diagonal; `rbf` is RbfPart(x).
  Eigen::MatrixXd Matrix(const Eigen::MatrixXd& x, const Eigen::MatrixXd& rbf) const;
  Eigen::MatrixXd Matrix(const Eigen::MatrixXd& x) const { return Matrix(x, RbfPart(x)); }
  // k(x_i, x*) for every row x_i of X (no noise: x* is a new point).
  Eigen::VectorXd Cross(const Eigen::MatrixXd& x, const Eigen::Vector3d& x_star) const;
  // k(x*, x*) without noise.
  double Self(const Eigen::Vector3d& x_star) const;

  // Chain rule through K: given G = dL/dK (symmetric, for K = Matrix(x)) and
  // rbf = RbfPart(x), adds dL/dX to `dx` and dL/d(log params) to `dlog_params`.
  void AddGradient(const Eigen::MatrixXd& x, const Eigen::MatrixXd& g, const Eigen::MatrixXd& rbf,
                   Eigen::MatrixXd* dx, Eigen::VectorXd* dlog_params) const;

 private:
  Kind kind_;
  Eigen::VectorXd log_params_;
  Eigen::VectorXd p_;  // exp(log_params_)
};

}  // namespace jgpm
