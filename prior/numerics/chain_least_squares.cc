#include "prior/numerics/chain_least_squares.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Cholesky>
#include <Eigen/SparseCholesky>

#include "io/base/error.h"

namespace jgpm {

void ChainNormalEquations::Reset(int frames, int border_size) {
  diagonal.assign(frames, Eigen::Matrix3d::Zero());
  lower.assign(std::max(frames - 1, 0), Eigen::Matrix3d::Zero());
  border.setZero(3 * frames, border_size);
  corner.setZero(border_size, border_size);
  gradient.setZero(3 * frames + border_size);
  cost = 0;
}

Eigen::VectorXd ChainNormalEquations::Diagonal() const {
  Eigen::VectorXd d(3 * NumFrames() + BorderSize());
  for (int f = 0; f < NumFrames(); ++f) d.segment<3>(3 * f) = diagonal[f].diagonal();
  d.tail(BorderSize()) = corner.diagonal();
  return d;
}

Eigen::MatrixXd ChainNormalEquations::Dense() const {
  const int t = NumFrames(), n = 3 * t + BorderSize();
  Eigen::MatrixXd h = Eigen::MatrixXd::Zero(n, n);
  for (int f = 0; f < t; ++f) {
    h.block<3, 3>(3 * f, 3 * f) = diagonal[f];
    if (f > 0) {
      h.block<3, 3>(3 * f, 3 * (f - 1)) = lower[f - 1];
      h.block<3, 3>(3 * (f - 1), 3 * f) = lower[f - 1].transpose();
    }
  }
  h.topRightCorner(3 * t, BorderSize()) = border;
  h.bottomLeftCorner(BorderSize(), 3 * t) = border.transpose();
  h.bottomRightCorner(BorderSize(), BorderSize()) = corner;
  return h;
}

bool SolveChainNormalEquations(const ChainNormalEquations& e, const Eigen::VectorXd& damping, Eigen::VectorXd* step) {
  const int t = e.NumFrames(), m = e.BorderSize(), n = 3 * t;
  JGPM_CHECK(damping.size() == n + m && e.gradient.size() == n + m);
  // A + damping, lower triangle, as a sparse matrix: block tridiagonal has no fill-in in
  // its natural order.
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(6 * n + 9 * std::max(t - 1, 0));
  for (int f = 0; f < t; ++f) {
    for (int j = 0; j < 3; ++j) {
      for (int i = j; i < 3; ++i) {
        entries.emplace_back(3 * f + i, 3 * f + j, e.diagonal[f](i, j) + (i == j ? damping[3 * f + i] : 0));
      }
    }
    if (f > 0) {
      for (int j = 0; j < 3; ++j) {
        for (int i = 0; i < 3; ++i) entries.emplace_back(3 * f + i, 3 * (f - 1) + j, e.lower[f - 1](i, j));
      }
    }
  }
  Eigen::SparseMatrix<double> a(n, n);
  a.setFromTriplets(entries.begin(), entries.end());
  const Eigen::SimplicialLLT<Eigen::SparseMatrix<double>, Eigen::Lower, Eigen::NaturalOrdering<int>> chain(a);
  if (chain.info() != Eigen::Success) return false;
  const Eigen::VectorXd chain_only = chain.solve(-e.gradient.head(n));  // A^-1 (-g_x)
  step->resize(n + m);
  if (m == 0) {
    *step = chain_only;
    return step->allFinite();
  }
  // C + damping - B^T A^-1 B, then the border's step and the chain's given it.
  const Eigen::MatrixXd eliminated = chain.solve(e.border);  // A^-1 B
  Eigen::MatrixXd schur = e.corner;
  schur.diagonal() += damping.tail(m);
  schur.noalias() -= e.border.transpose() * eliminated;
  const Eigen::LLT<Eigen::MatrixXd> border(schur);
  if (border.info() != Eigen::Success) return false;
  step->tail(m) = border.solve(-e.gradient.tail(m) - e.border.transpose() * chain_only);
  step->head(n) = chain_only - eliminated * step->tail(m);
  return step->allFinite();
}

ChainSolveSummary MinimizeChain(ChainLeastSquares& problem, int max_iterations, Eigen::VectorXd* p) {
  // Ceres's defaults (Solver::Options), so that the two take the same steps.
  constexpr double kInitialRadius = 1e4, kMaxRadius = 1e16, kMinRadius = 1e-32;
  constexpr double kMinDiagonal = 1e-6, kMaxDiagonal = 1e32, kMinRelativeDecrease = 1e-3;
  constexpr double kFunctionTolerance = 1e-6, kGradientTolerance = 1e-10, kParameterTolerance = 1e-8;
  constexpr int kMaxConsecutiveInvalidSteps = 5;

  const int n = 3 * problem.NumFrames() + problem.BorderSize();
  JGPM_CHECK(p->size() == n);
  ChainSolveSummary summary;
  auto finish = [&](Termination termination, std::string message) {
    summary.termination = termination;
    summary.message = std::move(message);
    return summary;
  };
  ChainNormalEquations equations;
  auto linearize = [&] {
    return problem.Linearize(*p, &equations) && std::isfinite(equations.cost) && equations.gradient.allFinite();
  };
  if (!linearize()) return finish(Termination::kNumericalFailure, "the start is not finite");
  summary.initial_cost = summary.final_cost = equations.cost;
  // Jacobi scaling: columns of J scaled by 1 / (1 + |J_i|), fixed from here on.
  const Eigen::ArrayXd scale = 1.0 / (1.0 + equations.Diagonal().array().max(0).sqrt());
  if (equations.gradient.lpNorm<Eigen::Infinity>() <= kGradientTolerance) {
    return finish(Termination::kConverged, "gradient tolerance reached");
  }
  double radius = kInitialRadius, decrease_factor = 2;
  int invalid_steps = 0;
  Eigen::VectorXd step, candidate;
  Eigen::ArrayXd scaled_diagonal;
  bool new_point = true;
  for (summary.iterations = 1; summary.iterations <= max_iterations; ++summary.iterations) {
    if (new_point) {
      // diag(J_s^T J_s) of the scaled Jacobian, clamped; kept while steps are rejected.
      scaled_diagonal = (equations.Diagonal().array() * scale.square()).max(kMinDiagonal).min(kMaxDiagonal);
      new_point = false;
    }
    // (J_s^T J_s + D / radius) y = -J_s^T r with p's step S y is (J^T J + D / (radius S^2)) dp = -J^T r.
    const Eigen::VectorXd damping = (scaled_diagonal / radius / scale.square()).matrix();
    double model_decrease = 0;
    bool valid = SolveChainNormalEquations(equations, damping, &step);
    if (valid) {
      // -(g^T dp + 1/2 dp^T H dp), with H dp = -g - damping dp.
      model_decrease = 0.5 * (-equations.gradient.dot(step) + step.dot(damping.cwiseProduct(step)));
      valid = std::isfinite(model_decrease) && model_decrease > 0;
    }
    if (!valid) {
      if (++invalid_steps >= kMaxConsecutiveInvalidSteps) {
        return finish(Termination::kNumericalFailure, "no valid step in " + std::to_string(invalid_steps) + " tries");
      }
      radius /= decrease_factor;
      decrease_factor *= 2;
      if (radius < kMinRadius) return finish(Termination::kConverged, "minimum trust region radius reached");
      continue;
    }
    invalid_steps = 0;
    candidate = *p + step;
    double candidate_cost = 0;
    if (!problem.Cost(candidate, &candidate_cost) || !std::isfinite(candidate_cost)) {
      candidate_cost = std::numeric_limits<double>::max();  // a rejected step
    }
    // A step that only shows convergence is not counted (nor is it by Ceres).
    if (step.norm() <= kParameterTolerance * (p->norm() + kParameterTolerance)) {
      --summary.iterations;
      return finish(Termination::kConverged, "parameter tolerance reached");
    }
    const double decrease = equations.cost - candidate_cost;
    if (std::abs(decrease) <= kFunctionTolerance * equations.cost) {
      --summary.iterations;
      return finish(Termination::kConverged, "function tolerance reached");
    }
    const double rho = decrease / model_decrease;
    if (rho > kMinRelativeDecrease) {
      radius = std::min(kMaxRadius, radius / std::max(1.0 / 3.0, 1.0 - std::pow(2.0 * rho - 1.0, 3)));
      decrease_factor = 2;
      *p = candidate;
      if (!linearize()) {
        return finish(Termination::kNumericalFailure, "the normal equations at an accepted point are not finite");
      }
      summary.final_cost = equations.cost;
      new_point = true;
      if (equations.gradient.lpNorm<Eigen::Infinity>() <= kGradientTolerance) {
        return finish(Termination::kConverged, "gradient tolerance reached");
      }
    } else {
      radius /= decrease_factor;
      decrease_factor *= 2;
    }
    if (radius < kMinRadius) return finish(Termination::kConverged, "minimum trust region radius reached");
  }
  summary.iterations = max_iterations;
  return finish(Termination::kNoConvergence, "maximum number of iterations reached");
}

}  // namespace jgpm
