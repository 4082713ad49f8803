#include "prior/kernel.h"

#include "io/error.h"
#include "prior/rbf_row.h"

namespace jgpm {

Kernel::Kernel(Kind kind, const Eigen::VectorXd& log_params)
    : kind_(kind), log_params_(log_params), p_(log_params.array().exp()) {
  JGPM_CHECK(log_params.size() == NumParams());
}

Eigen::MatrixXd Kernel::RbfPart(const Eigen::MatrixXd& x) const {
  JGPM_CHECK(x.cols() == 3);
  const int n = static_cast<int>(x.rows());
  if (kind_ == Kind::kLinear) return Eigen::MatrixXd::Zero(n, n);
  Eigen::MatrixXd k(n, n);
  for (int j = 0; j < n; ++j) {
    const Eigen::Vector3d q = x.row(j).transpose();
    RbfRow(x.data(), n, q.data(), signal_variance(), inverse_width(), k.col(j).data());
  }
  return k;
}

Eigen::MatrixXd Kernel::Matrix(const Eigen::MatrixXd& x, const Eigen::MatrixXd& rbf) const {
  Eigen::MatrixXd k = rbf;
  if (kind_ != Kind::kRbf) k.noalias() += linear_variance() * x * x.transpose();
  k.diagonal().array() += noise_variance();
  return k;
}

Eigen::VectorXd Kernel::Cross(const Eigen::MatrixXd& x, const Eigen::Vector3d& x_star) const {
  JGPM_CHECK(x.cols() == 3);
  Eigen::VectorXd k(x.rows());
  RbfRow(x.data(), static_cast<int>(x.rows()), x_star.data(), signal_variance(), inverse_width(), k.data());
  if (kind_ != Kind::kRbf) k.noalias() += linear_variance() * x * x_star;
  return k;
}

double Kernel::Self(const Eigen::Vector3d& x_star) const {
  return signal_variance() + linear_variance() * x_star.squaredNorm();
}

void Kernel::AddGradient(const Eigen::MatrixXd& x, const Eigen::MatrixXd& g,
                         const Eigen::MatrixXd& rbf, Eigen::MatrixXd* dx,
                         Eigen::VectorXd* dlog_params) const {
  JGPM_CHECK(g.rows() == x.rows() && g.cols() == x.rows() && dx->rows() == x.rows());
  JGPM_CHECK(rbf.rows() == x.rows() && dlog_params->size() == NumParams());
  if (kind_ != Kind::kLinear) {
    // H = G o K_rbf. dK_ij/dx_i = -b2 K_rbf_ij (x_i - x_j), and K is symmetric, so
    // dL/dx_i = -2 b2 (x_i sum_j H_ij - (H X)_i).
    const Eigen::MatrixXd h = g.cwiseProduct(rbf);
    const Eigen::VectorXd h_rows = h.rowwise().sum();
    dx->noalias() += -2.0 * inverse_width() * (h_rows.asDiagonal() * x - h * x);
    (*dlog_params)[0] += h.sum();  // d/d log b1
    // d/d log b2 = -b2/2 sum_ij H_ij |x_i - x_j|^2 = -b2 (sum_i h_i |x_i|^2 - sum_ij H_ij x_i.x_j).
    const Eigen::VectorXd norms = x.rowwise().squaredNorm();
    (*dlog_params)[1] += -inverse_width() * (h_rows.dot(norms) - (x.transpose() * h * x).trace());
  }
  if (kind_ != Kind::kRbf) {
    const Eigen::MatrixXd gx = g * x;
    dx->noalias() += 2.0 * linear_variance() * gx;
    (*dlog_params)[LinearIndex()] += linear_variance() * (x.transpose() * gx).trace();
  }
  // Noise 1/b: d(1/b)/d log b = -1/b.
  (*dlog_params)[NumParams() - 1] += -noise_variance() * g.trace();
}

}  // namespace jgpm
