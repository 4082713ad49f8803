#include "prior/inference.h"

#include <cmath>

#include <ceres/ceres.h>
#include <ceres/evaluation_callback.h>
#include <nanoflann.hpp>

#include "io/error.h"

namespace jgpm {
namespace {

using PackedLatent = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;

// The mean poses (and Jacobians) of all frames, computed in one batch before each
// evaluation from the latent points in `x`, which Ceres keeps at the evaluation point.
class BatchedMeans : public ceres::EvaluationCallback {
 public:
  BatchedMeans(const GaitModel& model, const std::vector<double>& x) : model_(model), x_(x) {}
  void PrepareForEvaluation(bool jacobians, bool new_point) override {
    if (!new_point && (!jacobians || have_jacobians_)) return;
    const Eigen::MatrixXd xs = Eigen::Map<const PackedLatent>(x_.data(), static_cast<int>(x_.size()) / 3, 3);
    poses = model_.MeanPoses(xs, jacobians ? &this->jacobians : nullptr);
    have_jacobians_ = jacobians;
  }
  Eigen::MatrixXd poses;                     // T x D
  std::array<Eigen::MatrixXd, 3> jacobians;  // d pose / d x_d, T x D each

 private:
  const GaitModel& model_;
  const std::vector<double>& x_;
  bool have_jacobians_ = false;
};

// (f_k(x_t) - u_tk) / s_k for the observed channels k of frame t.
class FrameResidual : public ceres::CostFunction {
 public:
  FrameResidual(const BatchedMeans& means, int t, Eigen::VectorXd observed, std::vector<int> channels,
                Eigen::VectorXd inverse_noise)
      : means_(means), t_(t), u_(std::move(observed)), channels_(std::move(channels)),
        inverse_noise_(std::move(inverse_noise)) {
    set_num_residuals(static_cast<int>(channels_.size()));
    mutable_parameter_block_sizes()->push_back(3);
  }
  bool Evaluate(double const* const*, double* residuals, double** jacobians) const override {
    for (size_t i = 0; i < channels_.size(); ++i) {
      const int k = channels_[i];
      residuals[i] = inverse_noise_[i] * (means_.poses(t_, k) - u_[i]);
      if (jacobians && jacobians[0]) {
        for (int d = 0; d < 3; ++d) jacobians[0][3 * i + d] = inverse_noise_[i] * means_.jacobians[d](t_, k);
      }
    }
    return true;
  }

 private:
  const BatchedMeans& means_;
  const int t_;
  const Eigen::VectorXd u_;  // the observed channels of frame t
  const std::vector<int> channels_;
  const Eigen::VectorXd inverse_noise_;
};

// With posture adaptation: (c_k + g_k (f_k(x_t) - c_k) + delta_k - u_tk) / s_k, one channel on
// the blocks x_t and s_k = (delta_k, g_k - 1). One block per channel and frame keeps J sparse:
// a frame-wide block on the whole style would make Ceres form J^T J from dense blocks (60%
// more time per solve with the offset alone).
class ChannelResidual : public ceres::SizedCostFunction<1, 3, 2> {
 public:
  ChannelResidual(const BatchedMeans& means, int t, int k, double observed, double inverse_noise, double centre)
      : means_(means), t_(t), k_(k), u_(observed), inverse_noise_(inverse_noise), centre_(centre) {}
  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override {
    const double f = means_.poses(t_, k_), a = parameters[1][1];  // a = g - 1
    residuals[0] = inverse_noise_ * (f + a * (f - centre_) + parameters[1][0] - u_);
    if (jacobians && jacobians[0]) {
      for (int d = 0; d < 3; ++d) jacobians[0][d] = inverse_noise_ * (1 + a) * means_.jacobians[d](t_, k_);
    }
    if (jacobians && jacobians[1]) {
      jacobians[1][0] = inverse_noise_;
      jacobians[1][1] = inverse_noise_ * (f - centre_);
    }
    return true;
  }

 private:
  const BatchedMeans& means_;
  const int t_, k_;
  const double u_, inverse_noise_, centre_;
};

// The style's priors on the D blocks s_k: the posture prior's W delta
// (prior/posture_prior.h), then the gains' (g_k - 1) / gain_std.
class StylePriorResidual : public ceres::CostFunction {
 public:
  StylePriorResidual(const PosturePrior& prior, double gain_std)
      : whitening_(prior.whitening()), inverse_gain_std_(1 / gain_std) {
    set_num_residuals(2 * static_cast<int>(whitening_.rows()));
    for (int k = 0; k < whitening_.cols(); ++k) mutable_parameter_block_sizes()->push_back(2);
  }
  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override {
    const int n = static_cast<int>(whitening_.cols());
    Eigen::Map<Eigen::VectorXd> offset(residuals, n), gain(residuals + n, n);
    offset.setZero();
    for (int k = 0; k < n; ++k) {
      offset += whitening_.col(k) * parameters[k][0];
      gain[k] = inverse_gain_std_ * parameters[k][1];
    }
    if (jacobians) {
      for (int k = 0; k < n; ++k) {
        if (!jacobians[k]) continue;
        // Row-major, 2n rows x 2 columns (delta_k, g_k - 1).
        Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, 2, Eigen::RowMajor>> j(jacobians[k], 2 * n, 2);
        j.setZero();
        j.col(0).head(n) = whitening_.col(k);
        j(n + k, 1) = inverse_gain_std_;
      }
    }
    return true;
  }

 private:
  const Eigen::MatrixXd whitening_;
  const double inverse_gain_std_;
};

// (x_t - g(x_{t-1})) / d, on the blocks x_{t-1} and x_t.
class DynamicsResidual : public ceres::SizedCostFunction<3, 3, 3> {
 public:
  DynamicsResidual(const GaitModel& model, double inverse_tolerance)
      : model_(model), inverse_tolerance_(inverse_tolerance) {}
  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override {
    const Eigen::Map<const Eigen::Vector3d> previous(parameters[0]), current(parameters[1]);
    Eigen::Matrix3d step_jacobian;
    const bool want = jacobians && jacobians[0];
    Eigen::Map<Eigen::Vector3d> r(residuals);
    r = inverse_tolerance_ * (current - model_.NextLatent(previous, nullptr, want ? &step_jacobian : nullptr));
    using RowMajor3 = Eigen::Matrix<double, 3, 3, Eigen::RowMajor>;
    if (want) {
      Eigen::Map<RowMajor3> j(jacobians[0]);
      j = -inverse_tolerance_ * step_jacobian;
    }
    if (jacobians && jacobians[1]) {
      Eigen::Map<RowMajor3> j(jacobians[1]);
      j = inverse_tolerance_ * RowMajor3::Identity();
    }
    return true;
  }

 private:
  const GaitModel& model_;
  const double inverse_tolerance_;
};

// (x_t - mean) / std per dimension.
class GaussianResidual : public ceres::SizedCostFunction<3, 3> {
 public:
  GaussianResidual(Eigen::Vector3d mean, Eigen::Vector3d inverse_std) : mean_(mean), inverse_std_(inverse_std) {}
  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override {
    const Eigen::Map<const Eigen::Vector3d> x(parameters[0]);
    Eigen::Map<Eigen::Vector3d> r(residuals);
    r = (x - mean_).cwiseProduct(inverse_std_);
    if (jacobians && jacobians[0]) {
      Eigen::Map<Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> j(jacobians[0]);
      j = inverse_std_.asDiagonal();
    }
    return true;
  }

 private:
  const Eigen::Vector3d mean_, inverse_std_;
};

// Checks the observations against the model; returns the observed channels.
std::vector<int> ObservedChannels(const GaitModel& model, const PoseObservations& o) {
  const int d = model.NumChannels();
  const Eigen::MatrixXd& u = o.poses_deg;
  if (u.rows() < 1 || u.cols() != d) {
    ThrowInputError("observed poses", "expected T x " + std::to_string(d) + " channels, got " +
                                          std::to_string(u.rows()) + " x " + std::to_string(u.cols()));
  }
  if (!o.observed.empty() && static_cast<int>(o.observed.size()) != d) {
    ThrowInputError("observed channels", "expected " + std::to_string(d) + " flags");
  }
  if (o.noise_std_deg.size() && (o.noise_std_deg.size() != d || !(o.noise_std_deg.array() >= 0).all())) {
    ThrowInputError("observation noise", "expected " + std::to_string(d) + " standard deviations >= 0");
  }
  std::vector<int> channels;
  for (int k = 0; k < d; ++k) {
    if (!o.observed.empty() && !o.observed[k]) continue;
    channels.push_back(k);
    for (int t = 0; t < u.rows(); ++t) {
      if (!std::isfinite(u(t, k))) {
        ThrowInputError("observed poses", "pose " + std::to_string(t) + ", channel " +
                                              model.data().set.channel_names[k] + " is not finite");
      }
    }
  }
  if (channels.empty()) ThrowInputError("observed channels", "at least one channel must be observed");
  return channels;
}

}  // namespace

bool InferenceOptions::Check(std::string* why) const {
  std::string why_posture;
  const char* problem = nullptr;
  if (!(observation_noise_deg > 0)) problem = "observation_noise_deg must be > 0";
  else if (!(dynamics_tolerance > 0)) problem = "dynamics_tolerance must be > 0";
  else if (!(adapted_dynamics_tolerance > 0)) problem = "adapted_dynamics_tolerance must be > 0";
  else if (!(gain_std > 0)) problem = "gain_std must be > 0";
  else if (adapt_posture && !posture.Check(&why_posture)) problem = why_posture.c_str();
  else if (max_iterations < 0 || adapted_max_iterations < 0) problem = "max_iterations must be >= 0";
  if (problem && why) *why = problem;  // `why` may be null
  return problem == nullptr;
}

struct SequenceProblem::Impl {
  Impl(const GaitModel& model, const PoseObservations& o, const InferenceOptions& options)
      : model(model), t(static_cast<int>(o.poses_deg.rows())),
        posture(options.adapt_posture
                    ? std::make_unique<PosturePrior>(PosturePrior::FromTrainingSet(model.data().set, options.posture))
                    : nullptr),
        x(3 * t, 0.0), style(posture ? 2 * model.NumChannels() : 0, 0.0), means(model, x), problem([this] {
          ceres::Problem::Options options;
          options.evaluation_callback = &means;
          return options;
        }()),
        max_iterations(options.adapt_posture ? options.adapted_max_iterations : options.max_iterations) {}
  const GaitModel& model;
  const int t;
  const std::unique_ptr<const PosturePrior> posture;  // when adapting
  std::vector<double> x;      // the parameter blocks: x_t at x.data() + 3 t
  std::vector<double> style;  // and, when adapting, s_k = (delta_k, g_k - 1) at style.data() + 2 k
  BatchedMeans means;         // before `problem`, which points to it
  ceres::Problem problem;
  const int max_iterations;

  using Strided = Eigen::Map<Eigen::VectorXd, 0, Eigen::InnerStride<2>>;
  Strided Offset() { return {style.data(), static_cast<Eigen::Index>(style.size() / 2)}; }
  Strided GainLessOne() { return {style.data() + 1, static_cast<Eigen::Index>(style.size() / 2)}; }

  // Empty posture_deg: zero; empty gain: ones.
  void Set(const Eigen::MatrixXd& latent, const Eigen::VectorXd& posture_deg, const Eigen::VectorXd& gain) {
    JGPM_CHECK(latent.rows() == t && latent.cols() == 3);
    Eigen::Map<PackedLatent>(x.data(), t, 3) = latent;
    const Eigen::Index d = static_cast<Eigen::Index>(style.size() / 2);
    JGPM_CHECK(posture_deg.size() == 0 || posture_deg.size() == d);
    JGPM_CHECK(gain.size() == 0 || gain.size() == d);
    std::fill(style.begin(), style.end(), 0.0);
    if (posture_deg.size()) Offset() = posture_deg;
    if (gain.size()) GainLessOne() = gain.array() - 1;
  }
  // The parameter blocks in the order of Evaluate's gradient: x_0 .. x_{T-1} [, s_k].
  std::vector<double*> Blocks() {
    std::vector<double*> blocks;
    for (int f = 0; f < t; ++f) blocks.push_back(x.data() + 3 * f);
    for (size_t k = 0; k < style.size(); k += 2) blocks.push_back(&style[k]);
    return blocks;
  }
};

SequenceProblem::SequenceProblem(const GaitModel& model, const PoseObservations& o, const InferenceOptions& options) {
  std::string why;
  if (!options.Check(&why)) ThrowInputError("inference options", why);
  const std::vector<int> channels = ObservedChannels(model, o);
  const int t = static_cast<int>(o.poses_deg.rows());
  impl_ = std::make_unique<Impl>(model, o, options);
  Eigen::VectorXd inverse_noise(channels.size());
  for (size_t i = 0; i < channels.size(); ++i) {
    const double noise = o.noise_std_deg.size() ? o.noise_std_deg[channels[i]] : 0.0;
    inverse_noise[i] = 1.0 / std::hypot(options.observation_noise_deg, noise);
  }
  for (int f = 0; f < t; ++f) {
    double* x = impl_->x.data() + 3 * f;
    if (impl_->posture) {
      for (size_t i = 0; i < channels.size(); ++i) {
        const int k = channels[i];
        impl_->problem.AddResidualBlock(
            new ChannelResidual(impl_->means, f, k, o.poses_deg(f, k), inverse_noise[i], model.data().set.mean[k]),
            nullptr, x, &impl_->style[2 * k]);
      }
      continue;
    }
    Eigen::VectorXd observed(channels.size());
    for (size_t i = 0; i < channels.size(); ++i) observed[i] = o.poses_deg(f, channels[i]);
    impl_->problem.AddResidualBlock(new FrameResidual(impl_->means, f, observed, channels, inverse_noise), nullptr, x);
  }
  if (impl_->posture) {
    std::vector<double*> blocks;
    for (size_t k = 0; k < impl_->style.size(); k += 2) blocks.push_back(&impl_->style[k]);
    impl_->problem.AddResidualBlock(new StylePriorResidual(*impl_->posture, options.gain_std), nullptr, blocks);
  }
  if (model.HasDynamics()) {
    const double tolerance = options.adapt_posture ? options.adapted_dynamics_tolerance : options.dynamics_tolerance;
    const double inverse_tolerance = 1.0 / (tolerance * MeanLatentStep(model));
    for (int f = 1; f < t; ++f) {
      impl_->problem.AddResidualBlock(new DynamicsResidual(model, inverse_tolerance), nullptr,
                                      impl_->x.data() + 3 * (f - 1), impl_->x.data() + 3 * f);
    }
  } else {
    const Eigen::MatrixXd& latent = model.latent();
    const Eigen::Vector3d mean = latent.colwise().mean();
    const Eigen::Vector3d std =
        ((latent.rowwise() - mean.transpose()).colwise().squaredNorm() / latent.rows()).cwiseSqrt().transpose();
    for (int f = 0; f < t; ++f) {
      impl_->problem.AddResidualBlock(new GaussianResidual(mean, std.cwiseMax(1e-9).cwiseInverse()), nullptr,
                                      impl_->x.data() + 3 * f);
    }
  }
}

SequenceProblem::~SequenceProblem() = default;

int SequenceProblem::NumFrames() const { return impl_->t; }

const PosturePrior* SequenceProblem::posture() const { return impl_->posture.get(); }

double SequenceProblem::Evaluate(const Eigen::MatrixXd& latent, Eigen::MatrixXd* gradient) {
  return Evaluate(latent, Eigen::VectorXd(), Eigen::VectorXd(), gradient, nullptr, nullptr);
}

double SequenceProblem::Evaluate(const Eigen::MatrixXd& latent, const Eigen::VectorXd& posture_deg,
                                 const Eigen::VectorXd& gain, Eigen::MatrixXd* gradient,
                                 Eigen::VectorXd* posture_gradient, Eigen::VectorXd* gain_gradient) {
  impl_->Set(latent, posture_deg, gain);
  double cost = 0;
  std::vector<double> g;
  ceres::Problem::EvaluateOptions options;
  options.parameter_blocks = impl_->Blocks();
  impl_->problem.Evaluate(options, &cost, nullptr, gradient || posture_gradient || gain_gradient ? &g : nullptr, nullptr);
  if (gradient) *gradient = Eigen::Map<const PackedLatent>(g.data(), impl_->t, 3);
  // The style blocks' gradient, (dE/d delta_k, dE/d g_k) per channel.
  using Strided = Eigen::Map<const Eigen::VectorXd, 0, Eigen::InnerStride<2>>;
  const Eigen::Index d = static_cast<Eigen::Index>(impl_->style.size() / 2);
  if (posture_gradient) *posture_gradient = Strided(g.data() + 3 * impl_->t, d);
  if (gain_gradient) *gain_gradient = Strided(g.data() + 3 * impl_->t + 1, d);
  return cost;
}

InferenceResult SequenceProblem::Solve(const Eigen::MatrixXd& initial_latent) {
  InferenceResult result;
  result.initial_latent = initial_latent;
  result.initial_objective = Evaluate(initial_latent, nullptr);
  ceres::Solver::Options options;
  options.max_num_iterations = impl_->max_iterations;
  // Frames couple only through the dynamics: J^T J is block tridiagonal. Eigen's sparse
  // Cholesky needs no BLAS threads, which would fight the validation's own threads.
  options.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
  options.sparse_linear_algebra_library_type = ceres::EIGEN_SPARSE;
  options.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  ceres::Solve(options, &impl_->problem, &summary);
  result.iterations = static_cast<int>(summary.iterations.size()) - 1;
  result.message = summary.message;
  result.termination = summary.termination_type == ceres::CONVERGENCE      ? Termination::kConverged
                       : summary.termination_type == ceres::NO_CONVERGENCE ? Termination::kNoConvergence
                                                                           : Termination::kNumericalFailure;
  result.latent = Eigen::Map<const PackedLatent>(impl_->x.data(), impl_->t, 3);
  const int d = impl_->model.NumChannels();
  result.posture_deg = impl_->posture ? Eigen::VectorXd(impl_->Offset()) : Eigen::VectorXd::Zero(d);
  result.gain = impl_->posture ? Eigen::VectorXd(impl_->GainLessOne().array() + 1) : Eigen::VectorXd::Ones(d);
  result.final_objective = impl_->posture ? Evaluate(result.latent, result.posture_deg, result.gain, nullptr, nullptr, nullptr)
                                          : Evaluate(result.latent, nullptr);
  // c + g (f - c) + delta, c the training mean posture.
  const Eigen::RowVectorXd& centre = impl_->model.data().set.mean;
  result.poses_deg = ((impl_->model.MeanPoses(result.latent).rowwise() - centre) * result.gain.asDiagonal()).rowwise() +
                     (centre + result.posture_deg.transpose());
  if (!result.poses_deg.allFinite()) {
    result.termination = Termination::kNumericalFailure;
    result.message = "the model's mean poses are not finite";
  }
  return result;
}

Eigen::MatrixXd NearestTrainingLatents(const GaitModel& model, const PoseObservations& observations) {
  const std::vector<int> columns = ObservedChannels(model, observations);
  const TrainingSet& set = model.data().set;
  const Eigen::MatrixXd& u = observations.poses_deg;
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

InferenceResult InferLatentSequence(const GaitModel& model, const PoseObservations& observations,
                                    const InferenceOptions& options) {
  SequenceProblem problem(model, observations, options);
  return problem.Solve(NearestTrainingLatents(model, observations));
}

}  // namespace jgpm
