#include "prior/inducing_gap.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numeric>
#include <string>

#include <lapacke.h>

#include "io/error.h"
#include "prior/cholesky.h"
#include "prior/kernel.h"
#include "prior/model_kind.h"
#include "prior/topology.h"
#include "prior/train.h"

namespace jgpm {
namespace {

// The faster of two evaluations with gradient (the first also warms the allocations up).
ObjectiveValue TimedEvaluation(const GpObjective& objective, const GpParameters& p, double* seconds) {
  GpParameters gradient;
  ObjectiveValue value;
  *seconds = std::numeric_limits<double>::infinity();
  for (int r = 0; r < 2; ++r) {
    const auto start = std::chrono::steady_clock::now();
    value = objective.Evaluate(p, &gradient);
    *seconds = std::min(*seconds, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  return value;
}

// Mean absolute error, degrees, of predicted normalised poses against the training poses.
double MeanErrorDeg(const TrainingSet& set, const Eigen::MatrixXd& predicted) {
  return ((predicted - set.y).array().rowwise() * set.scale.array()).abs().mean();
}

// Seconds per mean pose k(x*, inputs) weights, over queries cycling through `at`.
double MeanPoseSeconds(const Kernel& kernel, const Eigen::MatrixXd& inputs, const Eigen::MatrixXd& weights,
                       const Eigen::MatrixXd& at) {
  constexpr int kCalls = 1000;
  Eigen::RowVectorXd pose;
  double checksum = 0;  // uses every result, so none is optimised away
  const auto start = std::chrono::steady_clock::now();
  for (int k = 0; k < kCalls; ++k) {
    pose.noalias() = kernel.Cross(inputs, at.row(k % at.rows()).transpose()).transpose() * weights;
    checksum += pose[0];
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() / kCalls;
  JGPM_CHECK(std::isfinite(checksum));
  return seconds;
}

Eigen::MatrixXd Rows(const Eigen::MatrixXd& x, const std::vector<int>& rows, int count) {
  Eigen::MatrixXd out(count, x.cols());
  for (int k = 0; k < count; ++k) out.row(k) = x.row(rows[k]);
  return out;
}

}  // namespace

std::vector<int> GreedyPivotOrder(const Eigen::MatrixXd& k) {
  JGPM_CHECK(k.rows() == k.cols());
  const int n = static_cast<int>(k.rows());
  Eigen::MatrixXd factor = k;
  std::vector<lapack_int> pivots(n);
  lapack_int rank = 0;
  // info > 0 only says K is rank-deficient (expected: a smooth kernel over many points);
  // the pivots are still the greedy order up to the rank.
  const lapack_int info = LAPACKE_dpstrf(LAPACK_COL_MAJOR, 'L', n, factor.data(), n, pivots.data(), &rank, -1.0);
  JGPM_CHECK(info >= 0);
  std::vector<int> order(n);
  for (int j = 0; j < n; ++j) order[j] = static_cast<int>(pivots[j]) - 1;  // LAPACK counts from 1
  return order;
}

InducingGapReport MeasureInducingGap(const GaitModel& model, const std::vector<int>& ms) {
  const GaitModelData& data = model.data();
  const TrainingSet& set = data.set;
  const ModelSpec spec = SpecFor(data.kind, set.NumChannels());
  if (!spec.gaussian_process) ThrowInputError("model", std::string(ModelKindName(data.kind)) + " has no GP to make sparse");
  const int n = set.NumPoints();
  for (const int m : ms) {
    if (m < 3 || m > n) ThrowInputError("inducing inputs " + std::to_string(m), "expected 3 <= M <= N (" + std::to_string(n) + ")");
  }
  Topology topology;
  if (data.terms.topology) topology = MakeTopology(set, data.topology_options);
  const std::vector<Sequence> sequences = TrainingSequences(set);
  const GpObjective objective(set.y, sequences, data.terms.topology ? &topology : nullptr, data.terms);
  const GpParameters& p = data.params;

  InducingGapReport report;
  report.noise_std = std::exp(-0.5 * p.log_beta[2]);
  const ObjectiveValue exact = TimedEvaluation(objective, p, &report.exact_seconds);
  if (!exact.ok) ThrowInputError("model", "its exact objective cannot be evaluated: " + exact.why);
  report.exact = exact.total;
  const Kernel mapping(Kernel::Kind::kRbf, p.log_beta);
  {  // exact predictions: K_x. K^-1 Y (the channel scales W cancel in the mean)
    Cholesky chol;
    if (!chol.Compute(mapping.Matrix(p.x))) ThrowInputError("model", "mapping kernel: " + chol.why());
    const Eigen::MatrixXd weights = chol.Solve(set.y);
    report.exact_mean_error_deg = MeanErrorDeg(set, mapping.CrossMatrix(p.x, p.x, mapping.RbfCross(p.x, p.x)) * weights);
    report.exact_mean_seconds = MeanPoseSeconds(mapping, p.x, weights, p.x);
  }

  // Each GP's inputs, in greedy order over its noise-free kernel: the mapping's are all
  // latent points, the dynamics' every point with a next one in its sequence.
  const std::vector<int> mapping_order = GreedyPivotOrder(mapping.CrossMatrix(p.x, p.x, mapping.RbfCross(p.x, p.x)));
  Eigen::MatrixXd dynamics_inputs;
  std::vector<int> dynamics_order;
  if (data.terms.dynamics) {
    std::vector<int> rows;
    for (const Sequence& s : sequences) {
      for (int t = 0; t + 1 < s.length; ++t) rows.push_back(s.first + t);
    }
    dynamics_inputs = Rows(p.x, rows, static_cast<int>(rows.size()));
    const Kernel dynamics(Kernel::Kind::kRbfLinear, p.log_alpha);
    dynamics_order = GreedyPivotOrder(
        dynamics.CrossMatrix(dynamics_inputs, dynamics_inputs, dynamics.RbfCross(dynamics_inputs, dynamics_inputs)));
  }

  for (const int m : ms) {
    GpParameters sparse = p;
    sparse.u = Rows(p.x, mapping_order, m);
    if (data.terms.dynamics) {
      sparse.u_dynamics = Rows(dynamics_inputs, dynamics_order, std::min<int>(m, dynamics_inputs.rows()));
    }
    InducingGapPoint point;
    point.m = m;
    const ObjectiveValue bound = TimedEvaluation(objective, sparse, &point.seconds);
    if (!bound.ok) ThrowInputError("inducing inputs " + std::to_string(m), "the bound cannot be evaluated: " + bound.why);
    point.bound = bound.total;
    point.mapping_gap = bound.mapping - exact.mapping;
    point.dynamics_gap = bound.dynamics - exact.dynamics;
    // Predictions through the inducing inputs, in the bound's stable form (prior/sparse_gp.cc):
    // with L L^T = K_uu, A = L^-1 K_un / sigma and B = I + A A^T,
    // (sigma^2 K_uu + K_un K_nu)^-1 K_un Y = L^-T B^-1 A Y / sigma.
    const Eigen::MatrixXd k_un = mapping.CrossMatrix(sparse.u, p.x, mapping.RbfCross(sparse.u, p.x));
    Eigen::MatrixXd k_uu = mapping.CrossMatrix(sparse.u, sparse.u, mapping.RbfCross(sparse.u, sparse.u));
    k_uu.diagonal().array() += data.terms.inducing_jitter;
    Cholesky chol_uu, chol_b;
    const double sigma = report.noise_std;
    if (!chol_uu.Compute(k_uu)) ThrowInputError("inducing inputs " + std::to_string(m), chol_uu.why());
    const Eigen::MatrixXd a = chol_uu.HalfSolve(k_un) / sigma;
    Eigen::MatrixXd b = a * a.transpose();
    b.diagonal().array() += 1.0;
    if (!chol_b.Compute(b)) ThrowInputError("inducing inputs " + std::to_string(m), chol_b.why());
    const Eigen::MatrixXd weights = chol_uu.HalfSolveTransposed(chol_b.Solve(a * set.y)) / sigma;
    point.mean_error_deg = MeanErrorDeg(set, k_un.transpose() * weights);
    point.mean_seconds = MeanPoseSeconds(mapping, sparse.u, weights, p.x);
    report.points.push_back(point);
  }
  return report;
}

}  // namespace jgpm
