#include "prior/inference.h"

#include <cmath>

#include <ceres/first_order_function.h>
#include <ceres/gradient_problem.h>
#include <ceres/gradient_problem_solver.h>
#include <nanoflann.hpp>

#include "io/error.h"

namespace jgpm {
namespace {

// Mean distance between the latent points of consecutive training poses of a cycle.
double MeanLatentStep(const GaitModel& model) {
  const int poses = model.data().set.poses_per_gait;
  const Eigen::MatrixXd& x = model.latent();
  double sum = 0;
  int count = 0;
  for (int i = 0; i + 1 < x.rows(); ++i) {
    if ((i + 1) % poses == 0) continue;
    sum += (x.row(i + 1) - x.row(i)).norm();
    ++count;
  }
  return count ? std::max(sum / count, 1e-9) : 1.0;
}

using PackedLatent = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;

// Ceres view of the energy over the packed latent points (x_1, ..., x_T, row by row).
class CeresEnergy : public ceres::FirstOrderFunction {
 public:
  CeresEnergy(const SequenceEnergy& energy, int t) : energy_(energy), t_(t) {}
  bool Evaluate(const double* parameters, double* cost, double* gradient) const override {
    const Eigen::MatrixXd x = Eigen::Map<const PackedLatent>(parameters, t_, 3);
    Eigen::MatrixXd g;
    *cost = energy_.Evaluate(x, gradient ? &g : nullptr);
    if (!std::isfinite(*cost) || (gradient && !g.allFinite())) return false;
    if (gradient) Eigen::Map<PackedLatent>(gradient, t_, 3) = g;
    return true;
  }
  int NumParameters() const override { return 3 * t_; }

 private:
  const SequenceEnergy& energy_;
  const int t_;
};

// Latent point of the training pose nearest to each observed pose, on the observed channels
// in training standard deviations.
Eigen::MatrixXd NearestTrainingLatents(const GaitModel& model, const Eigen::MatrixXd& u,
                                       const std::vector<bool>& observed) {
  const TrainingSet& set = model.data().set;
  std::vector<int> columns;
  for (int k = 0; k < model.NumChannels(); ++k) {
    if (observed.empty() || observed[k]) columns.push_back(k);
  }
  const int n = set.NumPoints(), c = static_cast<int>(columns.size());
  Eigen::MatrixXd points(n, c), queries(u.rows(), c);
  for (int j = 0; j < c; ++j) {
    points.col(j) = set.y.col(columns[j]);
    queries.col(j) = (u.col(columns[j]).array() - set.mean[columns[j]]) / set.scale[columns[j]];
  }
  const nanoflann::KDTreeEigenMatrixAdaptor<Eigen::MatrixXd> tree(c, std::cref(points));
  Eigen::MatrixXd latent(u.rows(), 3);
  for (int t = 0; t < u.rows(); ++t) {
    const Eigen::VectorXd query = queries.row(t).transpose();
    Eigen::Index nearest = 0;
    double distance2 = 0;
    tree.query(query.data(), 1, &nearest, &distance2);
    latent.row(t) = model.latent().row(nearest);
  }
  return latent;
}

}  // namespace

SequenceEnergy::SequenceEnergy(const GaitModel& model, const PoseObservations& observations,
                               const InferenceOptions& options)
    : model_(model), u_(observations.poses_deg) {
  const TrainingSet& set = model.data().set;
  const int d = model.NumChannels();
  weight_ = Eigen::RowVectorXd::Zero(d);
  for (int k = 0; k < d; ++k) {
    if (!observations.observed.empty() && !observations.observed[k]) {
      u_.col(k).setZero();  // may hold anything, NaN included
      continue;
    }
    double s2 = std::pow(options.observation_noise * set.scale[k], 2);
    if (observations.noise_std_deg.size()) s2 += std::pow(observations.noise_std_deg[k], 2);
    weight_[k] = 1.0 / s2;
  }
  if (model.HasDynamics()) dynamics_weight_ = 1.0 / std::pow(options.dynamics_tolerance * MeanLatentStep(model), 2);
}

double SequenceEnergy::Evaluate(const Eigen::MatrixXd& x, Eigen::MatrixXd* gradient) const {
  JGPM_CHECK(x.rows() == u_.rows() && x.cols() == 3);
  const int t_count = static_cast<int>(x.rows());
  const Eigen::MatrixXd residual = model_.MeanPoses(x) - u_;  // T x D
  const Eigen::MatrixXd weighted = residual.array().rowwise() * weight_.array();
  double e = 0.5 * residual.cwiseProduct(weighted).sum();
  if (gradient) model_.MeanPoses(x, &weighted, gradient);
  for (int t = 0; t < t_count; ++t) {
    Eigen::Vector3d density_gradient;
    e -= model_.LogDensity(x.row(t).transpose(), gradient ? &density_gradient : nullptr);
    if (gradient) gradient->row(t) -= density_gradient.transpose();
  }
  if (dynamics_weight_ > 0) {
    for (int t = 1; t < t_count; ++t) {
      Eigen::Matrix3d jacobian;
      const Eigen::Vector3d r =
          x.row(t).transpose() - model_.NextLatent(x.row(t - 1).transpose(), nullptr, gradient ? &jacobian : nullptr);
      e += 0.5 * dynamics_weight_ * r.squaredNorm();
      if (gradient) {
        gradient->row(t) += dynamics_weight_ * r.transpose();
        gradient->row(t - 1) -= dynamics_weight_ * (jacobian.transpose() * r).transpose();
      }
    }
  }
  return e;
}

bool InferenceOptions::Check(std::string* why) const {
  if (!(observation_noise > 0)) *why = "observation_noise must be > 0";
  else if (!(dynamics_tolerance > 0)) *why = "dynamics_tolerance must be > 0";
  else if (max_iterations < 0) *why = "max_iterations must be >= 0";
  else return true;
  return false;
}

InferenceResult InferLatentSequence(const GaitModel& model, const PoseObservations& observations,
                                    const InferenceOptions& options) {
  std::string why;
  if (!options.Check(&why)) ThrowInputError("inference options", why);
  const int d = model.NumChannels();
  const Eigen::MatrixXd& u = observations.poses_deg;
  if (u.rows() < 1 || u.cols() != d) {
    ThrowInputError("observed poses", "expected T x " + std::to_string(d) + " channels, got " +
                                          std::to_string(u.rows()) + " x " + std::to_string(u.cols()));
  }
  if (!observations.observed.empty() && static_cast<int>(observations.observed.size()) != d) {
    ThrowInputError("observed channels", "expected " + std::to_string(d) + " flags");
  }
  if (observations.noise_std_deg.size() && (observations.noise_std_deg.size() != d ||
                                            !(observations.noise_std_deg.array() >= 0).all())) {
    ThrowInputError("observation noise", "expected " + std::to_string(d) + " standard deviations >= 0");
  }
  bool any = observations.observed.empty();
  for (int k = 0; k < d && !any; ++k) any = observations.observed[k];
  if (!any) ThrowInputError("observed channels", "at least one channel must be observed");
  for (int t = 0; t < u.rows(); ++t) {
    for (int k = 0; k < d; ++k) {
      if ((observations.observed.empty() || observations.observed[k]) && !std::isfinite(u(t, k))) {
        ThrowInputError("observed poses", "pose " + std::to_string(t) + ", channel " +
                                              model.data().set.channel_names[k] + " is not finite");
      }
    }
  }

  InferenceResult result;
  result.initial_latent = NearestTrainingLatents(model, u, observations.observed);
  const int t = static_cast<int>(u.rows());
  std::vector<double> x(3 * t);
  for (int i = 0; i < t; ++i) {
    for (int c = 0; c < 3; ++c) x[3 * i + c] = result.initial_latent(i, c);
  }
  const SequenceEnergy energy(model, observations, options);
  const ceres::GradientProblem problem(new CeresEnergy(energy, t));
  problem.Evaluate(x.data(), &result.initial_objective, nullptr);
  ceres::GradientProblemSolver::Options solver;
  solver.max_num_iterations = options.max_iterations;
  solver.logging_type = ceres::SILENT;
  ceres::GradientProblemSolver::Summary summary;
  ceres::Solve(solver, problem, x.data(), &summary);
  result.iterations = static_cast<int>(summary.iterations.size()) - 1;
  result.final_objective = summary.final_cost;
  result.latent = Eigen::Map<const PackedLatent>(x.data(), t, 3);
  result.poses_deg = model.MeanPoses(result.latent);
  return result;
}

}  // namespace jgpm
