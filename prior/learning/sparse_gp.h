// The inducing-point (sparse) Gaussian-process term: linear in N where the exact term
// (prior/learning/objective.h) is cubic. With M inducing inputs U, Q = K_nu K_uu^-1 K_un,
// sigma^2 the kernel's noise and Z the term's c output columns,
//
//   L = c/2 ln|sigma^2 I + Q| + 1/2 tr(Z^T (sigma^2 I + Q)^-1 Z) + c/(2 sigma^2) tr(K_nn - Q)
//
// the negated variational lower bound of Titsias (2009) on ln p(Z | X) (without the
// constant N c/2 ln 2 pi, as the exact term). Of the usual three approximations it is the
// one chosen because it is a bound: L >= the exact term for any U, equal when U = X, so
// minimising it over U moves the inducing inputs towards the exact objective and never
// over-fits; DTC is the same without the trace term (no bound, and it lets the noise
// shrink), FITC corrects the diagonal instead and is known to under-estimate the noise
// and over-fit (Bauer, van der Wilk & Rasmussen 2016).
//
// Evaluated through the M x M matrix P = sigma^2 K_uu + K_un K_nu (Woodbury and the
// determinant lemma): O(N M^2 + N M c) time, O(N (M + c)) memory; N x N is never formed.
// K_uu has no noise: it gets `inducing_jitter` on its diagonal (ObjectiveTerms: 1e-6, as
// GPflow's default; the data are normalised, so kernel variances are of order 1), and the
// Cholesky's adaptive jitter beyond that if it still cannot be factorised (reported).
#pragma once

#include <string>

#include <Eigen/Core>

#include "prior/numerics/kernel.h"

namespace jgpm {

// L above for latent points x (N x 3), inducing inputs u (M x 3) and outputs z (N x c).
// Sets *v = (sigma^2 I + Q)^-1 Z (dL/dZ, as K^-1 Z is for the exact term). With dx, adds
// weight * dL/dx to *dx, weight * dL/du to *du and weight * dL/d(log params) to
// *dlog_params. False, with `why` naming the term, when a matrix cannot be factorised.
bool SparseGpTerm(const Kernel& kernel, const Eigen::MatrixXd& x, const Eigen::MatrixXd& u,
                  const Eigen::MatrixXd& z, double weight, double inducing_jitter, const char* name, double* value,
                  Eigen::MatrixXd* v, Eigen::MatrixXd* dx, Eigen::MatrixXd* du, Eigen::VectorXd* dlog_params,
                  double* jitter, std::string* why);

// Weights V of the bound's predictive mean K_*u V of z at new inputs: V = (sigma^2 K_uu +
// K_un K_nu)^-1 K_un Z (M x c), computed through the same factors as the bound. False, with
// `why`, when a matrix cannot be factorised.
bool SparseGpMeanWeights(const Kernel& kernel, const Eigen::MatrixXd& x, const Eigen::MatrixXd& u,
                         const Eigen::MatrixXd& z, double inducing_jitter, Eigen::MatrixXd* weights, std::string* why);

}  // namespace jgpm
