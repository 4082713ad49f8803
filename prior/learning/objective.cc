#include "prior/learning/objective.h"

#include <cmath>

#include "io/base/error.h"
#include "prior/learning/sparse_gp.h"
#include "prior/numerics/cholesky.h"
#include "prior/numerics/kernel.h"

namespace jgpm {
namespace {

constexpr double kLog2Pi = 1.8378770664093453;

// The Gaussian-process term shared by the mapping and the dynamics:
//   L = c/2 ln|K| + 1/2 tr(Z^T K^-1 Z),  K = K(X), Z with c columns (no 2 pi term).
// Sets *a = K^-1 Z. With dx, adds weight * dL/dX to *dx and weight * dL/d(log params) to
// *dlog_params, through G = dL/dK = 1/2 (c K^-1 - A A^T). False, with `why`, when K cannot
// be factorised.
bool GpTerm(const Kernel& kernel, const Eigen::MatrixXd& x, const Eigen::MatrixXd& z, double weight,
            const char* name, double* value, Eigen::MatrixXd* a, Eigen::MatrixXd* dx,
            Eigen::VectorXd* dlog_params, double* jitter, std::string* why) {
  const Eigen::MatrixXd rbf = kernel.RbfPart(x);
  Cholesky chol;
  if (!chol.Compute(kernel.Matrix(x, rbf))) {
    *why = std::string(name) + ": " + chol.why();
    return false;
  }
  *jitter = std::max(*jitter, chol.jitter());
  *a = chol.Solve(z);
  const double c = z.cols();
  *value = 0.5 * c * chol.LogDeterminant() + 0.5 * z.cwiseProduct(*a).sum();
  if (dx) {
    Eigen::MatrixXd g = 0.5 * c * chol.Inverse();
    g.noalias() -= 0.5 * *a * a->transpose();
    g *= weight;
    kernel.AddGradient(x, g, rbf, dx, dlog_params);
  }
  return true;
}

// The exact term, or the sparse bound (prior/learning/sparse_gp.h) when `u` holds inducing inputs;
// then *du gets weight * dL/du.
bool Term(const Kernel& kernel, const Eigen::MatrixXd& x, const Eigen::MatrixXd& u, const Eigen::MatrixXd& z,
          double weight, double inducing_jitter, const char* name, double* value, Eigen::MatrixXd* a,
          Eigen::MatrixXd* dx, Eigen::MatrixXd* du, Eigen::VectorXd* dlog_params, double* jitter, std::string* why) {
  if (u.size() == 0) return GpTerm(kernel, x, z, weight, name, value, a, dx, dlog_params, jitter, why);
  return SparseGpTerm(kernel, x, u, z, weight, inducing_jitter, name, value, a, dx, du, dlog_params, jitter, why);
}

}  // namespace

int GpParameters::Size() const {
  return static_cast<int>(x.size() + log_beta.size() + log_alpha.size() + log_w.size() + u.size() +
                          u_dynamics.size());
}

void GpParameters::Pack(double* out) const {
  // Matrices row by row, so a point's three coordinates are adjacent.
  auto rows = [&out](const Eigen::MatrixXd& m) {
    for (int i = 0; i < m.rows(); ++i) {
      for (int d = 0; d < m.cols(); ++d) *out++ = m(i, d);
    }
  };
  rows(x);
  for (const Eigen::VectorXd* v : {&log_beta, &log_alpha, &log_w}) {
    for (int k = 0; k < v->size(); ++k) *out++ = (*v)[k];
  }
  rows(u);
  rows(u_dynamics);
}

void GpParameters::Unpack(const double* in) {
  auto rows = [&in](Eigen::MatrixXd* m) {
    for (int i = 0; i < m->rows(); ++i) {
      for (int d = 0; d < m->cols(); ++d) (*m)(i, d) = *in++;
    }
  };
  rows(&x);
  for (Eigen::VectorXd* v : {&log_beta, &log_alpha, &log_w}) {
    for (int k = 0; k < v->size(); ++k) (*v)[k] = *in++;
  }
  rows(&u);
  rows(&u_dynamics);
}

GpParameters GpParameters::ZerosLike() const {
  GpParameters zero;
  zero.x = Eigen::MatrixXd::Zero(x.rows(), x.cols());
  zero.log_beta = Eigen::VectorXd::Zero(log_beta.size());
  zero.log_alpha = Eigen::VectorXd::Zero(log_alpha.size());
  zero.log_w = Eigen::VectorXd::Zero(log_w.size());
  zero.u = Eigen::MatrixXd::Zero(u.rows(), u.cols());
  zero.u_dynamics = Eigen::MatrixXd::Zero(u_dynamics.rows(), u_dynamics.cols());
  return zero;
}

GpObjective::GpObjective(Eigen::MatrixXd y, std::vector<Sequence> sequences,
                         const Topology* topology, const ObjectiveTerms& terms)
    : y_(std::move(y)), sequences_(std::move(sequences)), topology_(topology), terms_(terms) {
  JGPM_CHECK(!terms_.topology || topology_ != nullptr);
  sequence_of_.assign(y_.rows(), -1);
  for (size_t s = 0; s < sequences_.size(); ++s) {
    for (int t = 0; t < sequences_[s].length; ++t) {
      JGPM_CHECK(sequences_[s].first + t < y_.rows());
      sequence_of_[sequences_[s].first + t] = static_cast<int>(s);
    }
  }
}

ObjectiveValue GpObjective::Evaluate(const GpParameters& p, GpParameters* gradient) const {
  std::vector<int> all(NumPoints());
  for (int i = 0; i < NumPoints(); ++i) all[i] = i;
  return EvaluateSubset(p, all, gradient);
}

ObjectiveValue GpObjective::EvaluateSubset(const GpParameters& p, const std::vector<int>& subset,
                                           GpParameters* gradient) const {
  JGPM_CHECK(p.x.rows() == NumPoints() && p.x.cols() == 3 && p.log_beta.size() == 3);
  JGPM_CHECK(p.log_alpha.size() == (terms_.dynamics ? 4 : 0));
  JGPM_CHECK(p.log_w.size() == (terms_.channel_scales ? NumChannels() : 0));
  JGPM_CHECK((p.u.size() == 0 || p.u.cols() == 3) && (p.u_dynamics.size() == 0 || p.u_dynamics.cols() == 3));
  JGPM_CHECK(p.u_dynamics.size() == 0 || terms_.dynamics);
  // Sparse terms are over all points (local learning's subsets are exact).
  JGPM_CHECK((p.u.size() == 0 && p.u_dynamics.size() == 0) || subset.size() == static_cast<size_t>(NumPoints()));
  ObjectiveValue value;
  if (gradient) *gradient = p.ZerosLike();
  const int m = static_cast<int>(subset.size());
  const int d = NumChannels();
  std::vector<int> position(NumPoints(), -1);  // row -> index in subset
  for (int k = 0; k < m; ++k) position[subset[k]] = k;

  Eigen::MatrixXd x(m, 3);
  Eigen::MatrixXd z(m, d);
  const Eigen::VectorXd w = p.log_w.size() ? Eigen::VectorXd(p.log_w.array().exp())
                                           : Eigen::VectorXd::Ones(d);
  for (int k = 0; k < m; ++k) {
    x.row(k) = p.x.row(subset[k]);
    z.row(k) = y_.row(subset[k]).cwiseProduct(w.transpose());
  }
  if (!x.allFinite() || !z.allFinite() || !p.u.allFinite() || !p.u_dynamics.allFinite()) {
    value.why = "non-finite latent points, inducing inputs, channel scales or data";
    return value;
  }
  Eigen::MatrixXd dx = Eigen::MatrixXd::Zero(m, 3);

  // Mapping.
  {
    Eigen::MatrixXd a;
    Eigen::VectorXd dbeta = Eigen::VectorXd::Zero(3);
    const Kernel kernel(terms_.linear_mapping ? Kernel::Kind::kLinear : Kernel::Kind::kRbf, p.log_beta);
    if (!Term(kernel, x, p.u, z, 1.0, terms_.inducing_jitter, "mapping kernel", &value.mapping, &a,
              gradient ? &dx : nullptr, gradient ? &gradient->u : nullptr, &dbeta, &value.jitter, &value.why)) {
      return value;
    }
    value.mapping += -m * p.log_w.sum() + 0.5 * m * d * kLog2Pi;
    if (gradient) {
      gradient->log_beta += dbeta;
      if (terms_.channel_scales) {
        // d/d ln w_j of 1/2 z_j^T K^-1 z_j (z_j = w_j y_j) is z_j^T K^-1 z_j.
        const Eigen::VectorXd za = z.cwiseProduct(a).colwise().sum().transpose();
        gradient->log_w += za - Eigen::VectorXd::Constant(d, m);
      }
    }
  }

  if (terms_.latent_prior) {
    value.latent = 0.5 * x.squaredNorm() + 0.5 * m * 3 * kLog2Pi;
    if (gradient) dx += x;
  }

  // Dynamics over consecutive pairs (t, t+1) of a sequence with both points in the subset.
  if (terms_.dynamics) {
    std::vector<int> in, out, first;
    for (int k = 0; k < m; ++k) {
      const int row = subset[k];
      const int s = sequence_of_[row];
      if (s < 0) continue;
      if (row == sequences_[s].first) first.push_back(k);
      if (row + 1 < sequences_[s].first + sequences_[s].length && position[row + 1] >= 0) {
        in.push_back(k);
        out.push_back(position[row + 1]);
      }
    }
    const double lambda = terms_.dynamics_weight;
    double dynamics = 0;
    for (int k : first) {
      dynamics += 0.5 * x.row(k).squaredNorm() + 0.5 * 3 * kLog2Pi;
      if (gradient) dx.row(k) += lambda * x.row(k);
    }
    if (!in.empty()) {
      const int pairs = static_cast<int>(in.size());
      Eigen::MatrixXd x_in(pairs, 3), x_out(pairs, 3);
      for (int k = 0; k < pairs; ++k) {
        x_in.row(k) = x.row(in[k]);
        x_out.row(k) = x.row(out[k]);
      }
      Eigen::MatrixXd b, dx_in = Eigen::MatrixXd::Zero(pairs, 3);
      Eigen::VectorXd dalpha = Eigen::VectorXd::Zero(4);
      double term;
      if (!Term(Kernel(Kernel::Kind::kRbfLinear, p.log_alpha), x_in, p.u_dynamics, x_out, lambda,
                terms_.inducing_jitter, "dynamics kernel", &term, &b, gradient ? &dx_in : nullptr,
                gradient ? &gradient->u_dynamics : nullptr, &dalpha, &value.jitter, &value.why)) {
        return value;
      }
      dynamics += term + 0.5 * pairs * 3 * kLog2Pi;
      if (gradient) {
        gradient->log_alpha += dalpha;
        for (int k = 0; k < pairs; ++k) {
          dx.row(in[k]) += dx_in.row(k);
          dx.row(out[k]) += lambda * b.row(k);
        }
      }
    }
    value.dynamics = lambda * dynamics;
  }

  if (terms_.topology) {
    const double scale = 1.0 / terms_.topology_sigma2;
    double energy = 0;
    for (int k = 0; k < m; ++k) {
      const int i = subset[k];
      const std::vector<int>& nb = topology_->neighbours[i];
      for (int dim = 0; dim < 3; ++dim) {
        double r = p.x(i, dim);
        for (size_t j = 0; j < nb.size(); ++j) r -= topology_->weights[dim](i, j) * p.x(nb[j], dim);
        energy += r * r;
        if (gradient) {
          dx(k, dim) += 2 * scale * r;
          for (size_t j = 0; j < nb.size(); ++j) {
            if (position[nb[j]] >= 0) {
              dx(position[nb[j]], dim) -= 2 * scale * r * topology_->weights[dim](i, j);
            }
          }
        }
      }
    }
    value.topology = scale * energy;
  }

  // Hyper-parameter priors p(b) ~ prod 1/b_i, p(a) ~ prod 1/a_i, p(W) Gaussian.
  value.priors = p.log_beta.sum() + p.log_alpha.sum();
  if (terms_.channel_scales) {
    const double kappa2 = terms_.scale_prior_width * terms_.scale_prior_width;
    value.priors += 0.5 * w.squaredNorm() / kappa2;
    if (gradient) gradient->log_w += (w.array().square() / kappa2).matrix();
  }
  if (gradient) {
    gradient->log_beta.array() += 1.0;
    gradient->log_alpha.array() += 1.0;
    if (terms_.fixed_inverse_width) {
      gradient->log_beta[1] = 0.0;
      if (terms_.linear_mapping) gradient->log_beta[0] = 0.0;
    }
    if (terms_.fixed_dynamics_noise && terms_.dynamics) gradient->log_alpha[3] = 0.0;
    for (int k = 0; k < m; ++k) gradient->x.row(subset[k]) = dx.row(k);
  }
  value.total = value.mapping + value.latent + value.dynamics + value.topology + value.priors;
  value.ok = std::isfinite(value.total);
  if (!value.ok) value.why = "objective is not finite";
  return value;
}

}  // namespace jgpm
