#include "prior/model/inference.h"

#include <array>
#include <cmath>

#include <nanoflann.hpp>

#include "io/base/error.h"
#include "prior/numerics/chain_least_squares.h"

namespace jgpm {
namespace {

using PackedLatent = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;

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
  else if (!(common_gain_std >= 0)) problem = "common_gain_std must be >= 0";
  else if (adapt_posture && !posture.Check(&why_posture)) problem = why_posture.c_str();
  else if (max_iterations < 0 || adapted_max_iterations < 0) problem = "max_iterations must be >= 0";
  if (problem && why) *why = problem;  // `why` may be null
  return problem == nullptr;
}

namespace {

// V with V^T V = (gain_std^2 I + common_gain_std^2 1 1^T)^-1, the gain prior's precision.
Eigen::MatrixXd GainWhitening(int channels, double gain_std, double common_gain_std) {
  // (s^2 I + c^2 1 1^T)^-1 = (I - gamma 1 1^T) / s^2 with gamma = c^2 / (s^2 + D c^2), and
  // V = (I - beta 1 1^T) / s has V^T V = (I - (2 beta - D beta^2) 1 1^T) / s^2: the root
  // of 2 beta - D beta^2 = gamma (real, as D gamma < 1).
  const double s2 = gain_std * gain_std, c2 = common_gain_std * common_gain_std;
  const double gamma = c2 / (s2 + channels * c2);
  const double beta = (1 - std::sqrt(1 - channels * gamma)) / channels;
  return (Eigen::MatrixXd::Identity(channels, channels) - Eigen::MatrixXd::Constant(channels, channels, beta)) / gain_std;
}

}  // namespace

// E as least squares over p = (x_1 .. x_T, s_1 .. s_D), s_k = (delta_k, g_k - 1) when
// adapting. The residuals, in order:
//   frames:   (c_k + g_k (f_k(x_t) - c_k) + delta_k - u_tk) / s_k, observed k of each t
//   style:    W delta, then V (g - 1) (adapting only; V^T V the gain prior's precision)
//   latent:   (x_t - g(x_{t-1})) / d for t > 1, or (x_t - mean) / std per dimension.
// Each frame's residuals touch x_t and the style; the dynamics x_{t-1} and x_t: the chain
// with a border of prior/numerics/chain_least_squares.h.
struct SequenceProblem::Impl : ChainLeastSquares {
  Impl(const GaitModel& model, const PoseObservations& o, const InferenceOptions& options)
      : model(model), t(static_cast<int>(o.poses_deg.rows())), channels(ObservedChannels(model, o)),
        observed(o.poses_deg),
        posture(options.adapt_posture
                    ? std::make_unique<PosturePrior>(PosturePrior::FromTrainingSet(model.data().set, options.posture))
                    : nullptr),
        max_iterations(options.adapt_posture ? options.adapted_max_iterations : options.max_iterations) {
    if (posture) {
      const int d = model.NumChannels();
      offset_precision = posture->whitening().transpose() * posture->whitening();
      gain_whitening = GainWhitening(d, options.gain_std, options.common_gain_std);
      gain_precision = gain_whitening.transpose() * gain_whitening;
    }
    inverse_noise.resize(static_cast<Eigen::Index>(channels.size()));
    for (size_t i = 0; i < channels.size(); ++i) {
      const double noise = o.noise_std_deg.size() ? o.noise_std_deg[channels[i]] : 0.0;
      inverse_noise[i] = 1.0 / std::hypot(options.observation_noise_deg, noise);
    }
    if (model.HasDynamics()) {
      const double tolerance = options.adapt_posture ? options.adapted_dynamics_tolerance : options.dynamics_tolerance;
      inverse_tolerance = 1.0 / (tolerance * MeanLatentStep(model));
    } else {
      const Eigen::MatrixXd& latent = model.latent();
      latent_mean = latent.colwise().mean().transpose();
      const Eigen::Vector3d std =
          ((latent.rowwise() - latent_mean.transpose()).colwise().squaredNorm() / latent.rows()).cwiseSqrt().transpose();
      latent_inverse_std = std.cwiseMax(1e-9).cwiseInverse();
    }
  }

  int NumFrames() const override { return t; }
  int BorderSize() const override { return posture ? 2 * model.NumChannels() : 0; }
  bool Cost(const Eigen::VectorXd& p, double* cost) override {
    *cost = Evaluate(p, nullptr, nullptr);
    return std::isfinite(*cost);
  }
  bool Linearize(const Eigen::VectorXd& p, ChainNormalEquations* equations) override {
    Evaluate(p, equations, nullptr);
    return std::isfinite(equations->cost) && equations->gradient.allFinite();
  }

  // 1/2 |r(p)|^2; with `equations` also J^T J and J^T r, with `residuals` r itself.
  double Evaluate(const Eigen::VectorXd& p, ChainNormalEquations* equations, Eigen::VectorXd* residuals) const {
    const int d = model.NumChannels(), m = BorderSize();
    const Eigen::MatrixXd latent = Eigen::Map<const PackedLatent>(p.data(), t, 3);
    const Eigen::Map<const Eigen::VectorXd> style(p.data() + 3 * t, m);
    std::array<Eigen::MatrixXd, 3> jacobians;
    const Eigen::MatrixXd poses = model.MeanPoses(latent, equations ? &jacobians : nullptr);
    if (equations) equations->Reset(t, m);
    const Eigen::RowVectorXd& centre = model.data().set.mean;  // c
    std::vector<double> r;
    double cost = 0;
    auto add = [&](double value) {
      cost += 0.5 * value * value;
      if (residuals) r.push_back(value);
    };
    for (int f = 0; f < t; ++f) {
      for (size_t i = 0; i < channels.size(); ++i) {
        const int k = channels[i];
        const double w = inverse_noise[i], g = posture ? 1 + style[2 * k + 1] : 1.0;
        const double shift = posture ? style[2 * k] : 0.0, centred = poses(f, k) - centre[k];
        const double value = w * (centre[k] + g * centred + shift - observed(f, k));
        add(value);
        if (!equations) continue;
        const Eigen::Vector3d jx = w * g * Eigen::Vector3d(jacobians[0](f, k), jacobians[1](f, k), jacobians[2](f, k));
        equations->diagonal[f] += jx * jx.transpose();
        equations->gradient.segment<3>(3 * f) += value * jx;
        if (!posture) continue;
        const Eigen::Vector2d js(w, w * centred);  // d / d (delta_k, g_k - 1)
        equations->border.block<3, 2>(3 * f, 2 * k) += jx * js.transpose();
        equations->corner.block<2, 2>(2 * k, 2 * k) += js * js.transpose();
        equations->gradient.segment<2>(3 * t + 2 * k) += value * js;
      }
    }
    if (posture) {
      const Eigen::MatrixXd& whitening = posture->whitening();
      const Eigen::Map<const Eigen::VectorXd, 0, Eigen::InnerStride<2>> delta(style.data(), d), gain_less_one(style.data() + 1, d);
      const Eigen::VectorXd whitened = whitening * delta, whitened_gain = gain_whitening * gain_less_one;
      for (Eigen::Index i = 0; i < whitened.size(); ++i) add(whitened[i]);
      for (int k = 0; k < d; ++k) add(whitened_gain[k]);
      if (equations) {
        const Eigen::VectorXd offset_gradient = offset_precision * delta, gain_gradient = gain_precision * gain_less_one;
        for (int k = 0; k < d; ++k) {
          equations->gradient[3 * t + 2 * k] += offset_gradient[k];
          equations->gradient[3 * t + 2 * k + 1] += gain_gradient[k];
          for (int j = 0; j < d; ++j) {
            equations->corner(2 * k, 2 * j) += offset_precision(k, j);
            equations->corner(2 * k + 1, 2 * j + 1) += gain_precision(k, j);
          }
        }
      }
    }
    if (model.HasDynamics()) {
      const double s = inverse_tolerance;
      for (int f = 1; f < t; ++f) {
        Eigen::Matrix3d step_jacobian;
        const Eigen::Vector3d previous = latent.row(f - 1).transpose();
        const Eigen::Vector3d value =
            s * (latent.row(f).transpose() - model.NextLatent(previous, nullptr, equations ? &step_jacobian : nullptr));
        for (int i = 0; i < 3; ++i) add(value[i]);
        if (!equations) continue;
        // d / d x_{t-1} = -s G, d / d x_t = s I.
        equations->diagonal[f - 1] += s * s * step_jacobian.transpose() * step_jacobian;
        equations->diagonal[f] += s * s * Eigen::Matrix3d::Identity();
        equations->lower[f - 1] -= s * s * step_jacobian;
        equations->gradient.segment<3>(3 * (f - 1)) -= s * step_jacobian.transpose() * value;
        equations->gradient.segment<3>(3 * f) += s * value;
      }
    } else {
      for (int f = 0; f < t; ++f) {
        const Eigen::Vector3d value = (latent.row(f).transpose() - latent_mean).cwiseProduct(latent_inverse_std);
        for (int i = 0; i < 3; ++i) add(value[i]);
        if (!equations) continue;
        equations->diagonal[f] += latent_inverse_std.cwiseAbs2().asDiagonal();
        equations->gradient.segment<3>(3 * f) += value.cwiseProduct(latent_inverse_std);
      }
    }
    if (equations) equations->cost = cost;
    if (residuals) *residuals = Eigen::Map<const Eigen::VectorXd>(r.data(), static_cast<Eigen::Index>(r.size()));
    return cost;
  }

  // p from the latent points (T x 3) and the style (empty offset: zero; empty gain: ones).
  Eigen::VectorXd Pack(const Eigen::MatrixXd& latent, const Eigen::VectorXd& posture_deg, const Eigen::VectorXd& gain) const {
    JGPM_CHECK(latent.rows() == t && latent.cols() == 3);
    const Eigen::Index d = BorderSize() / 2;
    JGPM_CHECK(posture_deg.size() == 0 || posture_deg.size() == d);
    JGPM_CHECK(gain.size() == 0 || gain.size() == d);
    Eigen::VectorXd p = Eigen::VectorXd::Zero(3 * t + BorderSize());
    Eigen::Map<PackedLatent>(p.data(), t, 3) = latent;
    if (posture_deg.size()) Offset(p) = posture_deg;
    if (gain.size()) GainLessOne(p) = gain.array() - 1;
    return p;
  }
  using Strided = Eigen::Map<Eigen::VectorXd, 0, Eigen::InnerStride<2>>;
  Strided Offset(Eigen::VectorXd& p) const { return {p.data() + 3 * t, BorderSize() / 2}; }
  Strided GainLessOne(Eigen::VectorXd& p) const { return {p.data() + 3 * t + 1, BorderSize() / 2}; }

  const GaitModel& model;
  const int t;
  const std::vector<int> channels;  // observed
  const Eigen::MatrixXd observed;   // u, T x D (only `channels` are read)
  const std::unique_ptr<const PosturePrior> posture;  // when adapting
  Eigen::MatrixXd offset_precision;  // W^T W, when adapting
  Eigen::MatrixXd gain_whitening, gain_precision;  // V and V^T V
  const int max_iterations;
  Eigen::VectorXd inverse_noise;    // 1 / s_k of `channels`
  double inverse_tolerance = 0;     // 1 / d, with dynamics
  Eigen::Vector3d latent_mean, latent_inverse_std;  // without
};

SequenceProblem::SequenceProblem(const GaitModel& model, const PoseObservations& o, const InferenceOptions& options) {
  std::string why;
  if (!options.Check(&why)) ThrowInputError("inference options", why);
  impl_ = std::make_unique<Impl>(model, o, options);
}

SequenceProblem::~SequenceProblem() = default;

int SequenceProblem::NumFrames() const { return impl_->t; }

const PosturePrior* SequenceProblem::posture() const { return impl_->posture.get(); }

double SequenceProblem::Evaluate(const Eigen::MatrixXd& latent, Eigen::MatrixXd* gradient) const {
  return Evaluate(latent, Eigen::VectorXd(), Eigen::VectorXd(), gradient, nullptr, nullptr);
}

double SequenceProblem::Evaluate(const Eigen::MatrixXd& latent, const Eigen::VectorXd& posture_deg,
                                 const Eigen::VectorXd& gain, Eigen::MatrixXd* gradient,
                                 Eigen::VectorXd* posture_gradient, Eigen::VectorXd* gain_gradient) const {
  const Eigen::VectorXd p = impl_->Pack(latent, posture_deg, gain);
  if (!gradient && !posture_gradient && !gain_gradient) return impl_->Evaluate(p, nullptr, nullptr);
  ChainNormalEquations equations;
  impl_->Evaluate(p, &equations, nullptr);
  const Eigen::VectorXd& g = equations.gradient;
  if (gradient) *gradient = Eigen::Map<const PackedLatent>(g.data(), impl_->t, 3);
  // The style's gradient, (dE/d delta_k, dE/d g_k) per channel.
  using Strided = Eigen::Map<const Eigen::VectorXd, 0, Eigen::InnerStride<2>>;
  const Eigen::Index d = impl_->BorderSize() / 2;
  if (posture_gradient) *posture_gradient = Strided(g.data() + 3 * impl_->t, d);
  if (gain_gradient) *gain_gradient = Strided(g.data() + 3 * impl_->t + 1, d);
  return equations.cost;
}

Eigen::VectorXd SequenceProblem::Residuals(const Eigen::MatrixXd& latent, const Eigen::VectorXd& posture_deg,
                                           const Eigen::VectorXd& gain) const {
  Eigen::VectorXd r;
  impl_->Evaluate(impl_->Pack(latent, posture_deg, gain), nullptr, &r);
  return r;
}

ChainNormalEquations SequenceProblem::NormalEquations(const Eigen::MatrixXd& latent, const Eigen::VectorXd& posture_deg,
                                                      const Eigen::VectorXd& gain) const {
  ChainNormalEquations equations;
  impl_->Evaluate(impl_->Pack(latent, posture_deg, gain), &equations, nullptr);
  return equations;
}

InferenceResult SequenceProblem::Solve(const Eigen::MatrixXd& initial_latent) {
  InferenceResult result;
  result.initial_latent = initial_latent;
  Eigen::VectorXd p = impl_->Pack(initial_latent, Eigen::VectorXd(), Eigen::VectorXd());
  result.initial_objective = impl_->Evaluate(p, nullptr, nullptr);
  const ChainSolveSummary summary = MinimizeChain(*impl_, impl_->max_iterations, &p);
  result.iterations = summary.iterations;
  result.message = summary.message;
  result.termination = summary.termination;
  result.latent = Eigen::Map<const PackedLatent>(p.data(), impl_->t, 3);
  const int d = impl_->model.NumChannels();
  result.posture_deg = impl_->posture ? Eigen::VectorXd(impl_->Offset(p)) : Eigen::VectorXd::Zero(d);
  result.gain = impl_->posture ? Eigen::VectorXd(impl_->GainLessOne(p).array() + 1) : Eigen::VectorXd::Ones(d);
  result.final_objective = impl_->Evaluate(p, nullptr, nullptr);
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
