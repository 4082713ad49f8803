#include "prior/learning/sparse_gp.h"

#include <algorithm>
#include <cmath>

#include "io/base/error.h"
#include "prior/numerics/cholesky.h"

namespace jgpm {

namespace {

// With L L^T = K_uu + jitter, A = L^-1 K_un / sigma (M x N) and B = I + A A^T, as GPflow's
// SGPR: sigma^2 I + Q = sigma^2 (I + A^T A), so ln|sigma^2 I + Q| = N ln sigma^2 + ln|B|,
// (sigma^2 I + Q)^-1 Z = (Z - A^T B^-1 A Z) / sigma^2 and tr Q = sigma^2 |A|^2. Every
// solve is against L or B, never K_uu itself: a smooth kernel makes K_uu nearly singular,
// and K_uu^-1 S computed directly then lost the trace term's accuracy (seen: a bound of
// -2e8 above an exact objective of +1.6e3 on the dynamics GP, whose noise is 1e-4).
struct Factors {
  Eigen::MatrixXd rbf_un, rbf_uu, k_un, a, aat;
  Cholesky chol_uu, chol_b;
};

bool Factorise(const Kernel& kernel, const Eigen::MatrixXd& x, const Eigen::MatrixXd& u, double inducing_jitter,
               const char* name, Factors* f, std::string* why) {
  JGPM_CHECK(x.cols() == 3 && u.cols() == 3 && u.rows() >= 1);
  f->rbf_un = kernel.RbfCross(u, x);
  f->rbf_uu = kernel.RbfCross(u, u);
  f->k_un = kernel.CrossMatrix(u, x, f->rbf_un);
  Eigen::MatrixXd k_uu = kernel.CrossMatrix(u, u, f->rbf_uu);
  k_uu.diagonal().array() += inducing_jitter;
  if (!f->chol_uu.Compute(k_uu)) {
    *why = std::string(name) + " (inducing inputs): " + f->chol_uu.why();
    return false;
  }
  f->a = f->chol_uu.HalfSolve(f->k_un) / std::sqrt(kernel.noise_variance());
  f->aat = f->a * f->a.transpose();
  Eigen::MatrixXd b = f->aat;
  b.diagonal().array() += 1.0;
  if (!f->chol_b.Compute(b)) {
    *why = std::string(name) + " (inducing inputs): " + f->chol_b.why();
    return false;
  }
  return true;
}

}  // namespace

bool SparseGpMeanWeights(const Kernel& kernel, const Eigen::MatrixXd& x, const Eigen::MatrixXd& u,
                         const Eigen::MatrixXd& z, double inducing_jitter, Eigen::MatrixXd* weights, std::string* why) {
  JGPM_CHECK(x.rows() == z.rows());
  Factors f;
  if (!Factorise(kernel, x, u, inducing_jitter, "mean", &f, why)) return false;
  // (sigma^2 K_uu + K_un K_nu)^-1 K_un Z = (sigma^2 L B L^T)^-1 L A Z sigma = L^-T B^-1 A Z / sigma.
  *weights = f.chol_uu.HalfSolveTransposed(f.chol_b.Solve(f.a * z)) / std::sqrt(kernel.noise_variance());
  return true;
}

bool SparseGpTerm(const Kernel& kernel, const Eigen::MatrixXd& x, const Eigen::MatrixXd& u,
                  const Eigen::MatrixXd& z, double weight, double inducing_jitter, const char* name, double* value,
                  Eigen::MatrixXd* v, Eigen::MatrixXd* dx, Eigen::MatrixXd* du, Eigen::VectorXd* dlog_params,
                  double* jitter, std::string* why) {
  JGPM_CHECK(x.rows() == z.rows());
  const int n = static_cast<int>(x.rows()), m = static_cast<int>(u.rows());
  const double c = z.cols();
  const double noise = kernel.noise_variance(), sigma = std::sqrt(noise);
  Factors f;
  if (!Factorise(kernel, x, u, inducing_jitter, name, &f, why)) return false;
  const Eigen::MatrixXd &rbf_un = f.rbf_un, &rbf_uu = f.rbf_uu, &a = f.a, &aat = f.aat;
  const Cholesky &chol_uu = f.chol_uu, &chol_b = f.chol_b;
  *jitter = std::max({*jitter, chol_uu.jitter(), chol_b.jitter()});
  const Eigen::MatrixXd az = a * z;               // M x c
  const Eigen::MatrixXd b_az = chol_b.Solve(az);  // B^-1 A Z
  *v = (z - a.transpose() * b_az) / noise;
  const double trace_q = noise * aat.trace();
  const double trace_knn = kernel.SelfSum(x);
  const double log_det = n * std::log(noise) + chol_b.LogDeterminant();
  *value = 0.5 * c * log_det + 0.5 * z.cwiseProduct(*v).sum() + 0.5 * c / noise * (trace_knn - trace_q);
  if (!dx) return true;

  // dL/dK_un = c P^-1 K_un - (P^-1 K_un Z) V^T - (c / sigma^2) K_uu^-1 K_un with
  // P = sigma^2 K_uu + K_un K_nu = sigma^2 L B L^T:  L^-T [c B^-1 A - (B^-1 A Z) V^T - c A] / sigma.
  const Eigen::MatrixXd b_a = chol_b.Solve(a);
  Eigen::MatrixXd inner = c * (b_a - a);
  inner.noalias() -= b_az * v->transpose();
  const Eigen::MatrixXd g_un = chol_uu.HalfSolveTransposed(inner) / sigma;
  // dL/dK_uu = -1/2 (c P^-1 S - (P^-1 K_un Z)(K_un V)^T) K_uu^-1 + c/(2 sigma^2) K_uu^-1 S K_uu^-1
  //          = L^-T [-1/2 (c B^-1 A A^T - (B^-1 A Z)(A V)^T) + c/2 A A^T] L^-1.
  // B^-1 A A^T = B^-1 (B - I) = I - B^-1.
  Eigen::MatrixXd b_aat = -chol_b.Solve(Eigen::MatrixXd::Identity(m, m));
  b_aat.diagonal().array() += 1.0;
  Eigen::MatrixXd middle = 0.5 * c * (aat - b_aat);
  middle.noalias() += 0.5 * b_az * (a * *v).transpose();
  const Eigen::MatrixXd half = chol_uu.HalfSolveTransposed(middle);                         // L^-T W
  Eigen::MatrixXd g_uu = chol_uu.HalfSolveTransposed(Eigen::MatrixXd(half.transpose())).transpose();  // L^-T W L^-1
  g_uu = 0.5 * (g_uu + g_uu.transpose()).eval();
  // dL/d sigma^2: 1/2 (c tr Sigma^-1 - |V|^2) with tr Sigma^-1 = (N - tr(B^-1 A A^T)) / sigma^2,
  // and the trace term's -c/(2 sigma^4) tr(K_nn - Q).
  const double trace_sigma_inv = (n - b_aat.trace()) / noise;
  const double d_noise =
      0.5 * (c * trace_sigma_inv - v->squaredNorm()) - 0.5 * c / (noise * noise) * (trace_knn - trace_q);

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
