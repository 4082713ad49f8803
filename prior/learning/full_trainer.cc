#include "prior/learning/full_trainer.h"

#include <chrono>
#include <cmath>

#include <ceres/first_order_function.h>
#include <ceres/gradient_problem.h>
#include <ceres/gradient_problem_solver.h>
#include <ceres/iteration_callback.h>

namespace jgpm {
namespace {

using Clock = std::chrono::steady_clock;

class ObjectiveFunction : public ceres::FirstOrderFunction {
 public:
  ObjectiveFunction(const GpObjective& objective, const GpParameters& shape)
      : objective_(objective), scratch_(shape), gradient_(shape.ZerosLike()) {}

  bool Evaluate(const double* parameters, double* cost, double* gradient) const override {
    scratch_.Unpack(parameters);
    const ObjectiveValue value = objective_.Evaluate(scratch_, gradient ? &gradient_ : nullptr);
    ++evaluations_;
    if (!value.ok) {
      last_failure_ = value.why;
      return false;  // Ceres shortens the step
    }
    max_jitter_ = std::max(max_jitter_, value.jitter);
    *cost = value.total;
    if (gradient) {
      gradient_.Pack(gradient);
      for (int k = 0; k < NumParameters(); ++k) {
        if (!std::isfinite(gradient[k])) {
          last_failure_ = "gradient is not finite";
          return false;
        }
      }
    }
    return true;
  }
  int NumParameters() const override { return scratch_.Size(); }

  mutable int evaluations_ = 0;
  mutable double max_jitter_ = 0;
  mutable std::string last_failure_;

 private:
  const GpObjective& objective_;
  mutable GpParameters scratch_;
  mutable GpParameters gradient_;
};

class ProgressReporter : public ceres::IterationCallback {
 public:
  ProgressReporter(const FullTrainingOptions& options, const ObjectiveFunction& function, std::string stage)
      : options_(options), function_(function), stage_(std::move(stage)), start_(Clock::now()),
        last_report_(start_), last_improvement_(start_) {}

  ceres::CallbackReturnType operator()(const ceres::IterationSummary& summary) override {
    const auto now = Clock::now();
    const double elapsed = std::chrono::duration<double>(now - start_).count();
    const bool last = summary.iteration >= options_.max_iterations;
    if (history_.empty() || summary.cost < history_.back()) last_improvement_ = now;
    history_.push_back(summary.cost);
    if (options_.progress &&
        (summary.iteration == 0 || last ||
         std::chrono::duration<double>(now - last_report_).count() >= options_.progress_interval_s)) {
      last_report_ = now;
      TrainingProgress p;
      p.stage = stage_;
      p.iteration = summary.iteration;
      p.max_iterations = options_.max_iterations;
      p.objective = summary.cost;
      p.jitter = function_.max_jitter_;
      p.elapsed_seconds = elapsed;
      p.rate = elapsed > 0 ? summary.iteration / elapsed : 0;
      p.seconds_since_improvement = std::chrono::duration<double>(now - last_improvement_).count();
      p.window_improvement = WindowImprovement(history_, options_.plateau_window);
      p.plateau_tolerance = options_.plateau_tolerance;
      options_.progress(p);
    }
    stopped_ = options_.budget.Exhausted(elapsed);
    if (!stopped_.empty()) return ceres::SOLVER_TERMINATE_SUCCESSFULLY;
    const int window = options_.plateau_window;
    if (static_cast<int>(history_.size()) > window) {
      const double before = history_[history_.size() - 1 - window];
      if (before - summary.cost < options_.plateau_tolerance * std::abs(summary.cost)) {
        converged_ = true;
        return ceres::SOLVER_TERMINATE_SUCCESSFULLY;
      }
    }
    return ceres::SOLVER_CONTINUE;
  }

  bool converged_ = false;
  std::string stopped_;  // why the budget ended training, if it did

 private:
  const FullTrainingOptions& options_;
  const ObjectiveFunction& function_;
  std::string stage_;
  Clock::time_point start_, last_report_, last_improvement_;
  std::vector<double> history_;
};

}  // namespace

TrainingSummary TrainFull(const GpObjective& objective, GpParameters* params,
                          const FullTrainingOptions& options) {
  const auto start = Clock::now();
  auto* function = new ObjectiveFunction(objective, *params);
  const ceres::GradientProblem problem(function);  // takes ownership
  std::vector<double> x(params->Size());
  params->Pack(x.data());

  ceres::GradientProblemSolver::Options solver;
  solver.line_search_direction_type = ceres::LBFGS;
  solver.max_num_iterations = options.max_iterations;
  solver.function_tolerance = 1e-12;  // the plateau test in ProgressReporter decides
  solver.gradient_tolerance = options.gradient_tolerance;
  solver.parameter_tolerance = 1e-12;
  solver.logging_type = ceres::SILENT;
  const bool sparse = params->u.size() > 0 || params->u_dynamics.size() > 0;
  ProgressReporter reporter(options, *function, sparse ? "sparse" : "full");
  solver.callbacks.push_back(&reporter);
  solver.update_state_every_iteration = false;

  ceres::GradientProblemSolver::Summary ceres_summary;
  ceres::Solve(solver, problem, x.data(), &ceres_summary);
  params->Unpack(x.data());

  TrainingSummary summary;
  summary.learning = sparse ? Learning::kSparse : Learning::kFull;
  summary.inducing = static_cast<int>(std::max(params->u.rows(), params->u_dynamics.rows()));
  summary.iterations = static_cast<int>(ceres_summary.iterations.size()) - 1;
  summary.evaluations = function->evaluations_;
  summary.initial_objective = ceres_summary.initial_cost;
  summary.final_objective = ceres_summary.final_cost;
  summary.max_jitter = function->max_jitter_;
  summary.message = ceres_summary.message;
  if (!reporter.stopped_.empty()) {
    summary.termination = Termination::kStopped;
    summary.message = reporter.stopped_;
  } else if (reporter.converged_) {
    summary.termination = Termination::kConverged;
    summary.message = "objective improved by less than " + std::to_string(options.plateau_tolerance) +
                      " (relative) over " + std::to_string(options.plateau_window) + " iterations";
  } else if (ceres_summary.termination_type == ceres::CONVERGENCE) {
    summary.termination = Termination::kConverged;
  } else if (ceres_summary.termination_type == ceres::NO_CONVERGENCE) {
    summary.termination = Termination::kNoConvergence;
  } else {
    summary.termination = Termination::kNumericalFailure;
    if (!function->last_failure_.empty()) summary.message += " (" + function->last_failure_ + ")";
  }
  summary.wall_seconds = std::chrono::duration<double>(Clock::now() - start).count();
  return summary;
}


}  // namespace jgpm
