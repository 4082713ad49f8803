#include "prior/eval/inducing_gap.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <string>

#include <ceres/first_order_function.h>
#include <ceres/gradient_problem.h>
#include <ceres/gradient_problem_solver.h>
#include <opencv2/imgproc.hpp>

#include "io/base/error.h"
#include "prior/learning/sparse_gp.h"
#include "prior/learning/topology.h"
#include "prior/model/model_kind.h"
#include "prior/model/train.h"
#include "prior/numerics/cholesky.h"
#include "prior/numerics/kernel.h"

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
  volatile double sink = 0;  // takes every result, so none is optimised away
  const auto start = std::chrono::steady_clock::now();
  for (int k = 0; k < kCalls; ++k) {
    pose.noalias() = kernel.Cross(inputs, at.row(k % at.rows()).transpose()).transpose() * weights;
    sink = sink + pose[0];
  }
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() / kCalls;
}

// The bound as a function of the inducing inputs alone (both GPs', row by row).
class InducingInputsBound : public ceres::FirstOrderFunction {
 public:
  InducingInputsBound(const GpObjective& objective, const GpParameters& p) : objective_(objective), p_(p) {}

  int NumParameters() const override { return static_cast<int>(p_.u.size() + p_.u_dynamics.size()); }
  bool Evaluate(const double* q, double* cost, double* gradient) const override {
    Copy(q, &p_.u, &p_.u_dynamics);
    const ObjectiveValue value = objective_.Evaluate(p_, gradient ? &gradient_ : nullptr);
    if (!value.ok) return false;  // Ceres shortens the step
    *cost = value.total;
    if (gradient) Copy(gradient_.u, gradient_.u_dynamics, gradient);
    return true;
  }

  static void Copy(const double* in, Eigen::MatrixXd* u, Eigen::MatrixXd* u_dynamics) {
    for (Eigen::MatrixXd* m : {u, u_dynamics}) {
      for (int r = 0; r < m->rows(); ++r) {
        for (int d = 0; d < 3; ++d) (*m)(r, d) = *in++;
      }
    }
  }
  static void Copy(const Eigen::MatrixXd& u, const Eigen::MatrixXd& u_dynamics, double* out) {
    for (const Eigen::MatrixXd* m : {&u, &u_dynamics}) {
      for (int r = 0; r < m->rows(); ++r) {
        for (int d = 0; d < 3; ++d) *out++ = (*m)(r, d);
      }
    }
  }

 private:
  const GpObjective& objective_;
  mutable GpParameters p_, gradient_;
};

// The bound after at most `iterations` L-BFGS iterations on the inducing inputs of `sparse`.
double OptimisedBound(const GpObjective& objective, const GpParameters& sparse, int iterations, int* used) {
  auto* function = new InducingInputsBound(objective, sparse);  // owned by the problem
  const ceres::GradientProblem problem(function);
  std::vector<double> q(function->NumParameters());
  InducingInputsBound::Copy(sparse.u, sparse.u_dynamics, q.data());
  ceres::GradientProblemSolver::Options options;
  options.max_num_iterations = iterations;
  options.logging_type = ceres::SILENT;
  ceres::GradientProblemSolver::Summary summary;
  ceres::Solve(options, problem, q.data(), &summary);
  *used = static_cast<int>(summary.iterations.size()) - 1;  // the first is the start
  return summary.final_cost;
}

Eigen::MatrixXd Rows(const Eigen::MatrixXd& x, const std::vector<int>& rows, int count) {
  Eigen::MatrixXd out(count, x.cols());
  for (int k = 0; k < count; ++k) out.row(k) = x.row(rows[k]);
  return out;
}

}  // namespace

InducingGapReport MeasureInducingGap(const GaitModel& model, const std::vector<int>& ms, int optimise_iterations) {
  const GaitModelData& data = model.data();
  const TrainingSet& set = data.set;
  const ModelSpec spec = SpecFor(data.kind, set.NumChannels());
  if (!spec.gaussian_process) {
    ThrowInputError("model", std::string(ModelKindName(data.kind)) + " has no GP to make sparse");
  }
  const int n = set.NumPoints();
  for (const int m : ms) {
    if (m < 3 || m > n) {
      ThrowInputError("inducing inputs " + std::to_string(m), "expected 3 <= M <= N (" + std::to_string(n) + ")");
    }
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
  const Eigen::MatrixXd k_nn = mapping.CrossMatrix(p.x, p.x, mapping.RbfCross(p.x, p.x));  // noise-free
  {  // exact predictions: K_x. K^-1 Y (the channel scales W cancel in the mean)
    Cholesky chol;
    if (!chol.Compute(mapping.Matrix(p.x))) ThrowInputError("model", "mapping kernel: " + chol.why());
    const Eigen::MatrixXd weights = chol.Solve(set.y);
    report.exact_mean_error_deg = MeanErrorDeg(set, k_nn * weights);
    report.exact_mean_seconds = MeanPoseSeconds(mapping, p.x, weights, p.x);
  }

  // Each GP's inputs, in greedy order over its noise-free kernel: the mapping's are all
  // latent points, the dynamics' every point with a next one in its sequence.
  const std::vector<int> mapping_order = GreedyPivotOrder(k_nn);
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
    if (!bound.ok) {
      ThrowInputError("inducing inputs " + std::to_string(m), "the bound cannot be evaluated: " + bound.why);
    }
    point.bound = point.optimised_bound = bound.total;
    point.mapping_gap = bound.mapping - exact.mapping;
    point.dynamics_gap = bound.dynamics - exact.dynamics;
    if (optimise_iterations > 0) {
      point.optimised_bound = OptimisedBound(objective, sparse, optimise_iterations, &point.optimiser_iterations);
    }
    Eigen::MatrixXd weights;
    std::string why;
    if (!SparseGpMeanWeights(mapping, p.x, sparse.u, set.y, data.terms.inducing_jitter, &weights, &why)) {
      ThrowInputError("inducing inputs " + std::to_string(m), why);
    }
    const Eigen::MatrixXd k_nu = mapping.CrossMatrix(p.x, sparse.u, mapping.RbfCross(p.x, sparse.u));
    point.mean_error_deg = MeanErrorDeg(set, k_nu * weights);
    point.mean_seconds = MeanPoseSeconds(mapping, sparse.u, weights, p.x);
    report.points.push_back(point);
  }
  return report;
}

cv::Mat InducingGapPlot(const InducingGapReport& report, const std::string& title) {
  JGPM_CHECK(!report.points.empty());
  const int width = 760, height = 480, left = 70, bottom = 50, top = 60, right = 30;
  cv::Mat image(height, width, CV_8UC3, cv::Scalar(255, 255, 255));
  const double scale = std::max(std::abs(report.exact), 1e-300);
  auto relative = [&](double gap) { return std::clamp(gap / scale, 1e-12, 1e300); };
  bool optimised = false;
  double m_hi = 0, lo = 1e300, hi = 0;
  for (const InducingGapPoint& p : report.points) {
    m_hi = std::max<double>(m_hi, p.m);
    lo = std::min({lo, relative(p.gap()), relative(p.optimised_gap(report.exact))});
    hi = std::max(hi, relative(p.gap()));
    optimised = optimised || p.optimiser_iterations > 0;
  }
  const double ly0 = std::floor(std::log10(lo)), ly1 = std::max(ly0 + 1, std::ceil(std::log10(hi)));
  auto to_pixel = [&](double m, double r) {
    return cv::Point(left + static_cast<int>(m / (1.05 * m_hi) * (width - left - right)),
                     top + static_cast<int>((1 - (std::log10(r) - ly0) / (ly1 - ly0)) * (height - top - bottom)));
  };
  auto text = [&](const std::string& s, cv::Point at, cv::Scalar colour = {0, 0, 0}, double scale = 0.42) {
    cv::putText(image, s, at, cv::FONT_HERSHEY_SIMPLEX, scale, colour, 1, cv::LINE_AA);
  };
  for (double e = ly0; e <= ly1; ++e) {  // decades
    const cv::Point a = to_pixel(0, std::pow(10, e)), b = to_pixel(1.05 * m_hi, std::pow(10, e));
    cv::line(image, a, b, e == -2 ? cv::Scalar(150, 150, 230) : cv::Scalar(228, 228, 228));
    text("1e" + std::to_string(static_cast<int>(e)), {18, a.y + 4});
  }
  if (ly0 <= -2 && -2 <= ly1) {
    text("1% of the objective", to_pixel(0.02 * m_hi, 1e-2) + cv::Point(0, -5), {90, 90, 200}, 0.38);
  }
  for (const InducingGapPoint& p : report.points) {
    const cv::Point at = to_pixel(p.m, std::pow(10, ly0));
    cv::line(image, {at.x, top}, at, cv::Scalar(228, 228, 228));
    text(std::to_string(p.m), {at.x - 14, at.y + 18});
  }
  text("inducing inputs M per GP", {width / 2 - 120, height - 12});
  text("(bound - exact) / |exact| at the model's parameters, log; labels: cost of an evaluation / exact",
       {left - 50, 22}, {0, 0, 0}, 0.45);
  text(title, {left - 50, 44}, {0, 0, 0}, 0.45);
  auto series = [&](auto gap, cv::Scalar colour, bool labels) {
    for (size_t k = 0; k < report.points.size(); ++k) {
      const InducingGapPoint& p = report.points[k];
      const cv::Point at = to_pixel(p.m, relative(gap(p)));
      if (k + 1 < report.points.size()) {
        const InducingGapPoint& q = report.points[k + 1];
        cv::line(image, at, to_pixel(q.m, relative(gap(q))), colour, 2, cv::LINE_AA);
      }
      cv::circle(image, at, 4, colour, cv::FILLED, cv::LINE_AA);
      if (!labels) continue;
      char label[32];
      std::snprintf(label, sizeof(label), "x%.2f", p.seconds / report.exact_seconds);
      text(label, at + cv::Point(6, -8), {60, 60, 60}, 0.38);
    }
  };
  series([](const InducingGapPoint& p) { return p.gap(); }, {180, 110, 30}, true);
  text("greedy inducing inputs", {width - right - 200, top + 14}, {180, 110, 30}, 0.42);
  if (optimised) {
    series([&](const InducingGapPoint& p) { return p.optimised_gap(report.exact); }, {40, 150, 40}, false);
    text("optimised (L-BFGS)", {width - right - 200, top + 32}, {40, 150, 40}, 0.42);
  }
  return image;
}

}  // namespace jgpm
