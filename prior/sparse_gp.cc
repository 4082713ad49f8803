#include "prior/sparse_gp.h"

#include <cmath>

#include "io/error.h"
#include "prior/cholesky.h"

namespace jgpm {

bool SparseGpTerm(const Kernel& kernel, const Eigen::MatrixXd& x, const Eigen::MatrixXd& u,
                  const Eigen::MatrixXd& z, double weight, const char* name, double* value, Eigen::MatrixXd* v,
                  Eigen::MatrixXd* dx, Eigen::MatrixXd* du, Eigen::VectorXd* dlog_params, double* jitter,
                  std::string* why) {
  JGPM_CHECK(x.rows() == z.rows() && x.cols() == 3 && u.cols() == 3 && u.rows() >= 1);
  const int n = static_cast<int>(x.rows()), m = static_cast<int>(u.rows());
  const double c = z.cols();
  const double noise = kernel.noise_variance();
  const Eigen::MatrixXd rbf_un = kernel.RbfCross(u, x), rbf_uu = kernel.RbfCross(u, u);
  const Eigen::MatrixXd k_un = kernel.CrossMatrix(u, x, rbf_un);
  const Eigen::MatrixXd k_uu = kernel.CrossMatrix(u, u, rbf_uu);
  Cholesky chol_uu, chol_p;
  if (!chol_uu.Compute(k_uu)) {
    *why = std::string(name) + " (inducing inputs): " + chol_uu.why();
    return false;
  }
  const Eigen::MatrixXd s = k_un * k_un.transpose();  // K_un K_nu
  Eigen::MatrixXd p = noise * k_uu;
  p.diagonal().array() += noise * chol_uu.jitter();  // P = sigma^2 (K_uu + jitter) + S
  p += s;
  if (!chol_p.Compute(p)) {
    *why = std::string(name) + " (inducing inputs): " + chol_p.why();
    return false;
  }
  *jitter = std::max({*jitter, chol_uu.jitter(), chol_p.jitter()});
  const Eigen::MatrixXd ky = k_un * z;        // M x c
  const Eigen::MatrixXd p_ky = chol_p.Solve(ky);
  *v = (z - k_un.transpose() * p_ky) / noise;  // (sigma^2 I + Q)^-1 Z
  const Eigen::MatrixXd uu_s = chol_uu.Solve(s);  // K_uu^-1 S
  const double trace_q = uu_s.trace();
  const double trace_knn = kernel.SelfSum(x);
  const double log_det = chol_p.LogDeterminant() - chol_uu.LogDeterminant() + (n - m) * std::log(noise);
  *value = 0.5 * c * log_det + 0.5 * z.cwiseProduct(*v).sum() + 0.5 * c / noise * (trace_knn - trace_q);
  if (!dx) return true;

  // dL/dK_un = c P^-1 K_un - (P^-1 K_un Z) V^T - (c / sigma^2) K_uu^-1 K_un.
  const Eigen::MatrixXd p_kun = chol_p.Solve(k_un), r = chol_uu.Solve(k_un);
  Eigen::MatrixXd g_un = c * p_kun - (c / noise) * r;
  g_un.noalias() -= p_ky * v->transpose();
  // dL/dK_uu = -1/2 (c P^-1 S - (P^-1 K_un Z)(K_un V)^T) K_uu^-1 + c/(2 sigma^2) K_uu^-1 S K_uu^-1.
  const Eigen::MatrixXd kv = k_un * *v;  // M x c
  const Eigen::MatrixXd p_s = chol_p.Solve(s);
  Eigen::MatrixXd left = c * p_s;
  left.noalias() -= p_ky * kv.transpose();
  Eigen::MatrixXd g_uu = -0.5 * chol_uu.Solve(left.transpose()).transpose();  // left K_uu^-1
  g_uu += 0.5 * c / noise * chol_uu.Solve(uu_s.transpose()).transpose();      // K_uu^-1 S K_uu^-1
  g_uu = 0.5 * (g_uu + g_uu.transpose()).eval();
  // dL/d sigma^2: tr of dL/dSigma = 1/2 (c tr Sigma^-1 - |V|^2), tr Sigma^-1 = (N - tr(P^-1 S)) /
  // sigma^2; and the trace term's -c/(2 sigma^4) tr(K_nn - Q).
  const double trace_sigma_inv = (n - p_s.trace()) / noise;
  const double d_noise = 0.5 * (c * trace_sigma_inv - v->squaredNorm()) - 0.5 * c / (noise * noise) * (trace_knn - trace_q);

  Eigen::MatrixXd du_local = Eigen::MatrixXd::Zero(m, 3), dx_local = Eigen::MatrixXd::Zero(n, 3);
  Eigen::VectorXd dlog = Eigen::VectorXd::Zero(kernel.NumParams());
  kernel.AddCrossGradient(u, x, g_un, rbf_un, &du_local, &dx_local, &dlog);
  kernel.AddCrossGradient(u, u, g_uu, rbf_uu, &du_local, &du_local, &dlog);
  kernel.AddSelfSumGradient(x, 0.5 * c / noise, &dx_local, &dlog);
  dlog[kernel.NumParams() - 1] += -noise * d_noise;  // sigma^2 = 1/b: d sigma^2 / d log b = -sigma^2
  *dx += weight * dx_local;
  *du += weight * du_local;
  *dlog_params += weight * dlog;
  return true;
}

}  // namespace jgpm
