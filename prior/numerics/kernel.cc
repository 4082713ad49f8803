#include "prior/numerics/kernel.h"

#include "io/base/error.h"
#include "prior/numerics/large_matrix.h"
#include "prior/numerics/rbf_row.h"

namespace jgpm {

Kernel::Kernel(Kind kind, const Eigen::VectorXd& log_params)
    : kind_(kind), log_params_(log_params), p_(log_params.array().exp()) {
  JGPM_CHECK(log_params.size() == NumParams());
}

Eigen::MatrixXd Kernel::RbfPart(const Eigen::MatrixXd& x) const { return RbfCross(x, x); }

Eigen::MatrixXd Kernel::Matrix(const Eigen::MatrixXd& x, Eigen::MatrixXd rbf) const {
  if (kind_ != Kind::kRbf) rbf.noalias() += linear_variance() * x * x.transpose();
  rbf.diagonal().array() += noise_variance();
  return rbf;
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

Eigen::MatrixXd Kernel::RbfCross(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) const {
  JGPM_CHECK(a.cols() == 3 && b.cols() == 3);
  const int n = static_cast<int>(a.rows());
  Eigen::MatrixXd k = LargeMatrix(n, b.rows());
  if (kind_ == Kind::kLinear) {
    k.setZero();
    return k;
  }
  for (int j = 0; j < b.rows(); ++j) {
    const Eigen::Vector3d q = b.row(j).transpose();
    RbfRow(a.data(), n, q.data(), signal_variance(), inverse_width(), k.col(j).data());
  }
  return k;
}

Eigen::MatrixXd Kernel::CrossMatrix(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b,
                                    const Eigen::MatrixXd& rbf) const {
  Eigen::MatrixXd k = rbf;
  if (kind_ != Kind::kRbf) k.noalias() += linear_variance() * a * b.transpose();
  return k;
}

void Kernel::AddCrossGradient(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b, const Eigen::MatrixXd& g,
                              const Eigen::MatrixXd& rbf, Eigen::MatrixXd* da, Eigen::MatrixXd* db,
                              Eigen::VectorXd* dlog_params) const {
  JGPM_CHECK(g.rows() == a.rows() && g.cols() == b.rows() && rbf.rows() == a.rows() && rbf.cols() == b.rows());
  JGPM_CHECK(da->rows() == a.rows() && db->rows() == b.rows() && dlog_params->size() == NumParams());
  if (kind_ != Kind::kLinear) {
    // H = G o C_rbf; dC_ij/da_i = -b2 C_rbf_ij (a_i - b_j) = -dC_ij/db_j.
    const Eigen::MatrixXd h = g.cwiseProduct(rbf);
    const Eigen::VectorXd h_rows = h.rowwise().sum(), h_cols = h.colwise().sum().transpose();
    const Eigen::MatrixXd hb = h * b;
    const Eigen::MatrixXd hta = h.transpose() * a;
    da->noalias() += -inverse_width() * (h_rows.asDiagonal() * a - hb);
    db->noalias() += -inverse_width() * (h_cols.asDiagonal() * b - hta);
    (*dlog_params)[0] += h.sum();
    // d/d log b2 = -b2/2 sum_ij H_ij |a_i - b_j|^2.
    (*dlog_params)[1] += -0.5 * inverse_width() *
                         (h_rows.dot(a.rowwise().squaredNorm()) + h_cols.dot(b.rowwise().squaredNorm()) -
                          2 * a.cwiseProduct(hb).sum());
  }
  if (kind_ != Kind::kRbf) {
    const Eigen::MatrixXd gb = g * b;
    da->noalias() += linear_variance() * gb;
    db->noalias() += linear_variance() * g.transpose() * a;
    (*dlog_params)[LinearIndex()] += linear_variance() * a.cwiseProduct(gb).sum();
  }
}

double Kernel::SelfSum(const Eigen::MatrixXd& x) const {
  return x.rows() * signal_variance() + linear_variance() * x.squaredNorm();
}

void Kernel::AddSelfSumGradient(const Eigen::MatrixXd& x, double weight, Eigen::MatrixXd* dx,
                                Eigen::VectorXd* dlog_params) const {
  if (kind_ != Kind::kLinear) (*dlog_params)[0] += weight * x.rows() * signal_variance();
  if (kind_ != Kind::kRbf) {
    *dx += 2 * weight * linear_variance() * x;
    (*dlog_params)[LinearIndex()] += weight * linear_variance() * x.squaredNorm();
  }
}

}  // namespace jgpm
