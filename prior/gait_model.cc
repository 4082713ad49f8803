#include "prior/gait_model.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include <Eigen/Cholesky>

#include "io/asf.h"
#include "io/error.h"
#include "prior/cholesky.h"
#include "prior/kernel.h"
#include "prior/rbf_row.h"

namespace jgpm {
namespace {

constexpr double kTwoPi = 6.283185307179586;

void Require(bool condition, const std::string& source, const std::string& what) {
  if (!condition) ThrowInputError(source, "inconsistent model: " + what);
}

// The linear baseline: y_normalised = basis x.
class PcaGaitModel : public GaitModel {
 public:
  PcaGaitModel(GaitModelData data, const std::string& source) : GaitModel(std::move(data), source) {
    const int d = NumChannels();
    Require(data_.pca_basis.rows() == d && data_.pca_basis.cols() == 3 && data_.pca_basis.allFinite(),
            source, "PCA basis must be channels x 3");
    score_variance_ = (data_.params.x.colwise().squaredNorm() / NumPoints()).transpose();
    score_variance_ = score_variance_.cwiseMax(1e-12);
    const Eigen::MatrixXd residual = data_.set.y - data_.params.x * data_.pca_basis.transpose();
    residual_variance_ = residual.squaredNorm() / residual.size();
  }

  void Predict(const Eigen::Vector3d& x, Eigen::VectorXd* pose_deg, double* variance) const override {
    *pose_deg = Denormalise(data_.pca_basis * x);
    if (variance) *variance = residual_variance_;
  }

  Eigen::MatrixXd MeanPoses(const Eigen::MatrixXd& xs, std::array<Eigen::MatrixXd, 3>* jacobians) const override {
    const TrainingSet& s = data_.set;
    if (jacobians) {
      for (int d = 0; d < 3; ++d) {
        (*jacobians)[d] = (data_.pca_basis.col(d).transpose().cwiseProduct(s.scale)).replicate(xs.rows(), 1);
      }
    }
    return ((xs * data_.pca_basis.transpose()).array().rowwise() * s.scale.array()).rowwise() + s.mean.array();
  }

  double LogDensity(const Eigen::Vector3d& x, Eigen::Vector3d* gradient) const override {
    if (gradient) *gradient = -x.cwiseQuotient(score_variance_);
    return -0.5 * x.cwiseAbs2().cwiseQuotient(score_variance_).sum();
  }

  double LogPrior(const Eigen::Vector3d& x, Eigen::Vector3d* gradient) const override {
    return LogDensity(x, gradient);
  }

 private:
  Eigen::Vector3d score_variance_;
  double residual_variance_ = 0;
};

class GpGaitModel : public GaitModel {
 public:
  GpGaitModel(GaitModelData data, const std::string& source)
      : GaitModel(std::move(data), source),
        kernel_(Kernel::Kind::kRbf, data_.params.log_beta) {
    const GpParameters& p = data_.params;
    Require(p.log_beta.size() == 3 && p.log_beta.allFinite(), source, "mapping kernel needs 3 finite log hyper-parameters");
    Require(p.log_alpha.size() == (data_.terms.dynamics ? 4 : 0) && p.log_alpha.allFinite(), source,
            "dynamics kernel needs 4 finite log hyper-parameters");
    Require(p.log_w.size() == (data_.terms.channel_scales ? NumChannels() : 0) && p.log_w.allFinite(), source,
            "channel scales must be one finite value per channel");
    if (!chol_.Compute(kernel_.Matrix(p.x))) ThrowInputError(source, "mapping kernel: " + chol_.why());
    // The mean is Y^T K^-1 k(x): the channel scales W cancel out of it.
    a_ = chol_.Solve(data_.set.y);
    if (data_.terms.dynamics) {
      std::vector<int> in, out;
      const int poses = data_.set.poses_per_gait;
      for (int i = 0; i < NumPoints(); ++i) {
        if ((i + 1) % poses != 0) {
          in.push_back(i);
          out.push_back(i + 1);
        }
      }
      x_in_.resize(static_cast<int>(in.size()), 3);
      Eigen::MatrixXd x_out(static_cast<int>(out.size()), 3);
      for (size_t k = 0; k < in.size(); ++k) {
        x_in_.row(k) = p.x.row(in[k]);
        x_out.row(k) = p.x.row(out[k]);
      }
      dynamics_ = std::make_unique<Kernel>(Kernel::Kind::kRbfLinear, p.log_alpha);
      if (!dynamics_chol_.Compute(dynamics_->Matrix(x_in_))) {
        ThrowInputError(source, "dynamics kernel: " + dynamics_chol_.why());
      }
      b_ = dynamics_chol_.Solve(x_out);
    }
  }

  void Predict(const Eigen::Vector3d& x, Eigen::VectorXd* pose_deg, double* variance) const override {
    const Eigen::VectorXd k = kernel_.Cross(data_.params.x, x);
    *pose_deg = Denormalise(a_.transpose() * k);
    if (variance) *variance = std::max(0.0, kernel_.Self(x) - chol_.HalfSolve(k).squaredNorm());
  }

  double LogPrior(const Eigen::Vector3d& x, Eigen::Vector3d* gradient) const override {
    const Eigen::MatrixXd& xs = data_.params.x;
    const Eigen::VectorXd k = kernel_.Cross(xs, x);
    const Eigen::VectorXd half = chol_.HalfSolve(k);
    // Floor the variance at the noise level so ln stays finite on the training points.
    const double floor = kernel_.noise_variance();
    const double variance = std::max(floor, kernel_.Self(x) - half.squaredNorm());
    const double d = NumChannels();
    double value = LogDensity(x, gradient) - 0.5 * d * std::log(variance);
    if (gradient && variance > floor) {
      // dk_i/dx = -b2 (x - x_i) k_i, so d variance/dx = 2 b2 sum_i (K^-1 k)_i k_i (x - x_i).
      const Eigen::VectorXd weights = chol_.HalfSolveTransposed(half).cwiseProduct(k);
      const Eigen::Vector3d dvariance =
          2 * kernel_.inverse_width() * (weights.sum() * x - xs.transpose() * weights);
      *gradient -= 0.5 * d / variance * dvariance;
    }
    return value;
  }

  Eigen::VectorXd Variances(const Eigen::MatrixXd& xs) const override {
    // All points at once: v_j = k** - |L^-1 k_j|^2.
    const Eigen::MatrixXd k = CrossMatrix(xs);
    const Eigen::VectorXd quadratic = chol_.HalfSolve(k.transpose()).colwise().squaredNorm().transpose();
    return (Eigen::VectorXd::Constant(xs.rows(), kernel_.signal_variance()) - quadratic).cwiseMax(0.0);
  }

  Eigen::MatrixXd MeanPoses(const Eigen::MatrixXd& xs, std::array<Eigen::MatrixXd, 3>* jacobians) const override {
    const Eigen::MatrixXd k = CrossMatrix(xs);  // T x N
    const TrainingSet& s = data_.set;
    if (jacobians) {
      // dk_ti/dx_td = b2 (x_id - x_td) k_ti, so d pose_t / d x_td = scale o (b2 (k o (x_d - x_td)) A).
      const Eigen::MatrixXd& train = data_.params.x;
      for (int d = 0; d < 3; ++d) {
        const Eigen::MatrixXd kd =
            (k.array().rowwise() * train.col(d).transpose().array()).matrix() - xs.col(d).asDiagonal() * k;
        (*jacobians)[d] = ((kernel_.inverse_width() * kd * a_).array().rowwise() * s.scale.array()).matrix();
      }
    }
    return ((k * a_).array().rowwise() * s.scale.array()).rowwise() + s.mean.array();
  }

  bool HasDynamics() const override { return dynamics_ != nullptr; }

  Eigen::Vector3d NextLatent(const Eigen::Vector3d& x, double* variance, Eigen::Matrix3d* jacobian) const override {
    if (!dynamics_) return GaitModel::NextLatent(x, variance, jacobian);
    const Eigen::VectorXd k = dynamics_->Cross(x_in_, x);
    if (variance) *variance = std::max(0.0, dynamics_->Self(x) - dynamics_chol_.HalfSolve(k).squaredNorm());
    if (jacobian) {
      // k_i = a1 exp(-a2/2 |x - x_i|^2) + a3 x_i.x: dk_i/dx = a2 (x_i - x) rbf_i + a3 x_i.
      const Eigen::VectorXd rbf = k - dynamics_->linear_variance() * x_in_ * x;
      const Eigen::MatrixXd dk = dynamics_->inverse_width() *
                                     (rbf.asDiagonal() * (x_in_.rowwise() - x.transpose())) +
                                 dynamics_->linear_variance() * x_in_;  // N x 3
      *jacobian = b_.transpose() * dk;
    }
    return b_.transpose() * k;
  }

 private:
  // k(x*, x_i) for every row x* of xs and training point x_i: T x N.
  Eigen::MatrixXd CrossMatrix(const Eigen::MatrixXd& xs) const {
    const Eigen::MatrixXd& train = data_.params.x;
    Eigen::MatrixXd k_transposed(train.rows(), xs.rows());
    for (int t = 0; t < xs.rows(); ++t) {
      const Eigen::Vector3d q = xs.row(t).transpose();
      RbfRow(train.data(), static_cast<int>(train.rows()), q.data(), kernel_.signal_variance(),
             kernel_.inverse_width(), k_transposed.col(t).data());
    }
    return k_transposed.transpose();
  }

  Kernel kernel_;
  Cholesky chol_;
  Eigen::MatrixXd a_;
  std::unique_ptr<Kernel> dynamics_;
  Cholesky dynamics_chol_;
  Eigen::MatrixXd x_in_, b_;
};

}  // namespace

std::unique_ptr<GaitModel> GaitModel::Create(GaitModelData data, const std::string& source) {
  if (data.kind == ModelKind::kPca) return std::unique_ptr<GaitModel>(new PcaGaitModel(std::move(data), source));
  return std::unique_ptr<GaitModel>(new GpGaitModel(std::move(data), source));
}

GaitModel::GaitModel(GaitModelData data, const std::string& source) : data_(std::move(data)) {
  TrainingSet& set = data_.set;
  const int d = static_cast<int>(set.channel_names.size());
  Require(d > 0 && static_cast<int>(set.channel_joints.size()) == d, source, "channel names and joints differ in number");
  Require(set.poses_per_gait > 0 && set.NumGaits() > 0 && set.NumLayers() > 0, source, "no training poses");
  const int n = set.NumLayers() * set.NumGaits() * set.poses_per_gait;
  Require(set.y_deg.rows() == n && set.y_deg.cols() == d && set.y_deg.allFinite(), source,
          "training poses must be " + std::to_string(n) + " x " + std::to_string(d) + " finite values");
  Require(set.mean.size() == d && set.scale.size() == d && set.mean.allFinite() &&
              (set.scale.array() > 0).all(), source, "channel means and positive scales needed");
  ComputeDerivedFields(&set);
  Require(data_.params.x.rows() == n && data_.params.x.cols() == 3 && data_.params.x.allFinite(), source,
          "latent points must be " + std::to_string(n) + " x 3 finite values");
  if (!data_.gait_order.empty()) {
    std::vector<int> sorted = data_.gait_order;
    std::sort(sorted.begin(), sorted.end());
    std::vector<int> expected(set.NumGaits());
    std::iota(expected.begin(), expected.end(), 0);
    Require(sorted == expected, source, "gait order must be a permutation of the gaits");
    Require(data_.prior_coordinates.rows() == n && data_.prior_coordinates.cols() == 3, source,
            "prior coordinates must be one row per training point");
  }
  skeleton_ = ParseAsf(data_.skeleton_asf, source + " (embedded skeleton of " + data_.skeleton_trial + ")");
  kinematics_ = std::make_unique<GaitPoseKinematics>(skeleton_, source);
  Require(kinematics_->layout().channel_names() == set.channel_names, source,
          "the skeleton's gait channels differ from the model's");

  layers_by_scale_.resize(set.NumLayers());
  std::iota(layers_by_scale_.begin(), layers_by_scale_.end(), 0);
  std::sort(layers_by_scale_.begin(), layers_by_scale_.end(),
            [&](int a, int b) { return set.layer_scales[a] < set.layer_scales[b]; });

  // Density width: the median distance from a training point to its nearest neighbour.
  const Eigen::MatrixXd& x = data_.params.x;
  std::vector<double> nearest(n, std::numeric_limits<double>::infinity());
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      if (j != i) nearest[i] = std::min(nearest[i], (x.row(i) - x.row(j)).squaredNorm());
    }
  }
  std::nth_element(nearest.begin(), nearest.begin() + n / 2, nearest.end());
  density_width_ = std::max(1e-6, std::sqrt(nearest[n / 2]));
}

Eigen::VectorXd GaitModel::Variances(const Eigen::MatrixXd& xs) const {
  Eigen::VectorXd variances(xs.rows());
  Eigen::VectorXd pose;
  for (int i = 0; i < xs.rows(); ++i) Predict(xs.row(i).transpose(), &pose, &variances[i]);
  return variances;
}

Eigen::Vector3d GaitModel::NextLatent(const Eigen::Vector3d& x, double* variance, Eigen::Matrix3d* jacobian) const {
  if (variance) *variance = 0;
  if (jacobian) jacobian->setIdentity();
  return x;
}

Eigen::VectorXd GaitModel::Denormalise(const Eigen::VectorXd& y) const {
  return data_.set.mean.transpose() + data_.set.scale.transpose().cwiseProduct(y);
}

double GaitModel::LogDensity(const Eigen::Vector3d& x, Eigen::Vector3d* gradient) const {
  const Eigen::MatrixXd& xs = data_.params.x;
  const double h2 = density_width_ * density_width_;
  const Eigen::VectorXd d2 = (xs.rowwise() - x.transpose()).rowwise().squaredNorm();
  const double nearest = d2.minCoeff();
  // Log-sum-exp around the nearest point, so far-away x does not underflow to ln 0.
  const Eigen::VectorXd w = (-(d2.array() - nearest) / (2 * h2)).exp();
  const double sum = w.sum();
  if (gradient) *gradient = (xs.transpose() * w / sum - x) / h2;
  return std::log(sum) - nearest / (2 * h2) - std::log(static_cast<double>(xs.rows())) -
         3 * std::log(density_width_) - 1.5 * std::log(kTwoPi);
}

void GaitModel::JointPositions(const Eigen::VectorXd& pose_deg, Eigen::Matrix3Xd* joints) const {
  JGPM_CHECK(pose_deg.size() == NumChannels());
  kinematics_->Compute(pose_deg.data(), joints);
}

Eigen::Vector3d GaitModel::LatentAt(int layer, int gait_position, int pose) const {
  return data_.params.x.row(data_.set.Row(layer, data_.gait_order[gait_position], pose)).transpose();
}

Eigen::Vector3d GaitModel::ManifoldToLatent(const ManifoldPoint& point) const {
  JGPM_CHECK(HasManifold());
  const TrainingSet& set = data_.set;
  const int poses = set.poses_per_gait, gaits = set.NumGaits();
  const bool torus = data_.topology_options.shape == TopologyShape::kTorus;
  double p = point.phase * poses;
  p -= poses * std::floor(p / poses);
  const int p0 = static_cast<int>(std::floor(p)) % poses, p1 = (p0 + 1) % poses;
  const double wp = p - std::floor(p);
  double g = point.gait;
  int g0, g1;
  double wg;
  if (torus) {
    g -= gaits * std::floor(g / gaits);
    g0 = static_cast<int>(std::floor(g)) % gaits;
    g1 = (g0 + 1) % gaits;
    wg = g - std::floor(g);
  } else {
    g = std::clamp(g, 0.0, static_cast<double>(gaits - 1));
    g0 = std::min(static_cast<int>(std::floor(g)), gaits - 1);
    g1 = std::min(g0 + 1, gaits - 1);
    wg = g - g0;
  }
  auto in_layer = [&](int layer) -> Eigen::Vector3d {
    return (1 - wg) * ((1 - wp) * LatentAt(layer, g0, p0) + wp * LatentAt(layer, g0, p1)) +
           wg * ((1 - wp) * LatentAt(layer, g1, p0) + wp * LatentAt(layer, g1, p1));
  };
  const std::vector<int>& by_scale = layers_by_scale_;
  const auto scale_of = [&](int k) { return set.layer_scales[by_scale[k]]; };
  if (by_scale.size() == 1 || point.scale <= scale_of(0)) return in_layer(by_scale.front());
  if (point.scale >= scale_of(static_cast<int>(by_scale.size()) - 1)) return in_layer(by_scale.back());
  int k = 0;
  while (point.scale > scale_of(k + 1)) ++k;
  const double ws = (point.scale - scale_of(k)) / (scale_of(k + 1) - scale_of(k));
  return (1 - ws) * in_layer(by_scale[k]) + ws * in_layer(by_scale[k + 1]);
}

ManifoldPoint GaitModel::LatentToManifold(const Eigen::Vector3d& x) const {
  JGPM_CHECK(HasManifold());
  const TrainingSet& set = data_.set;
  std::vector<int> position(set.NumGaits());
  for (int k = 0; k < set.NumGaits(); ++k) position[data_.gait_order[k]] = k;
  const auto latent = [&](const Eigen::Vector3d& q) -> Eigen::Vector3d {
    return ManifoldToLatent({q[0], q[1], q[2]});
  };
  const double lowest = set.layer_scales[layers_by_scale_.front()];
  const double highest = set.layer_scales[layers_by_scale_.back()];
  // The interpolation can fold, so start Gauss-Newton (numeric Jacobian, halving steps
  // that do not help) from the 8 nearest training points and keep the best end.
  const Eigen::VectorXd d2 = (data_.params.x.rowwise() - x.transpose()).rowwise().squaredNorm();
  std::vector<int> order(d2.size());
  std::iota(order.begin(), order.end(), 0);
  const int starts = std::min<int>(8, static_cast<int>(order.size()));
  std::partial_sort(order.begin(), order.begin() + starts, order.end(),
                    [&](int a, int b) { return d2[a] < d2[b]; });
  Eigen::Vector3d best(0, 0, 1);
  double best_error = std::numeric_limits<double>::infinity();
  for (int s = 0; s < starts; ++s) {
    const TrainingPoint& start = set.points[order[s]];
    Eigen::Vector3d m(static_cast<double>(start.pose) / set.poses_per_gait, position[start.gait],
                      set.layer_scales[start.layer]);
    double error = (latent(m) - x).squaredNorm();
    for (int iteration = 0; iteration < 20 && error > 1e-24; ++iteration) {
      const Eigen::Vector3d r = latent(m) - x;
      Eigen::Matrix3d j;
      const double h = 1e-5;
      for (int c = 0; c < 3; ++c) {
        Eigen::Vector3d plus = m, minus = m;
        plus[c] += h;
        minus[c] -= h;
        j.col(c) = (latent(plus) - latent(minus)) / (2 * h);
      }
      Eigen::Vector3d step = (j.transpose() * j + 1e-12 * Eigen::Matrix3d::Identity()).ldlt().solve(-j.transpose() * r);
      if (!step.allFinite()) break;
      bool improved = false;
      for (int halving = 0; halving < 10 && !improved; ++halving, step *= 0.5) {
        Eigen::Vector3d next = m + step;
        next[2] = std::clamp(next[2], lowest, highest);
        const double next_error = (latent(next) - x).squaredNorm();
        if (next_error < error) {
          m = next;
          error = next_error;
          improved = true;
        }
      }
      if (!improved) break;
    }
    if (error < best_error) best_error = error, best = m;
  }
  ManifoldPoint point;
  point.phase = best[0] - std::floor(best[0]);
  point.gait = data_.topology_options.shape == TopologyShape::kTorus
                   ? best[1] - set.NumGaits() * std::floor(best[1] / set.NumGaits())
                   : std::clamp(best[1], 0.0, set.NumGaits() - 1.0);
  point.scale = best[2];
  return point;
}

double TrainingReconstructionErrorMm(const GaitModel& model) {
  const TrainingSet& set = model.data().set;
  double total = 0;
  Eigen::VectorXd pose;
  Eigen::Matrix3Xd estimated, truth;
  for (int i = 0; i < model.NumPoints(); ++i) {
    model.Predict(model.latent().row(i).transpose(), &pose, nullptr);
    model.JointPositions(pose, &estimated);
    model.JointPositions(set.y_deg.row(i).transpose(), &truth);
    total += (estimated - truth).colwise().norm().mean();
  }
  return total / model.NumPoints();
}

std::string DescribeModel(const GaitModel& model) {
  const GaitModelData& d = model.data();
  const TrainingSet& set = d.set;
  char line[512];
  std::string out;
  std::snprintf(line, sizeof(line), "%s model: %d latent points (%d gaits x %d poses x %d layer(s)), %d channels, split %s\n",
                std::string(ModelKindName(d.kind)).c_str(), model.NumPoints(), set.NumGaits(),
                set.poses_per_gait, set.NumLayers(), model.NumChannels(), d.split.c_str());
  out += line;
  if (d.params.log_beta.size() == 3) {
    const Eigen::Vector3d b = d.params.log_beta.array().exp();
    std::snprintf(line, sizeof(line), "mapping kernel: b1 %.4g, b2 %.4g (fixed), noise std %.4g\n", b[0], b[1], 1 / std::sqrt(b[2]));
    out += line;
  }
  if (d.params.log_alpha.size() == 4) {
    const Eigen::Vector4d a = d.params.log_alpha.array().exp();
    std::snprintf(line, sizeof(line), "dynamics kernel: a1 %.4g, a2 %.4g, a3 %.4g, noise std %.4g (fixed)\n", a[0], a[1], a[2], 1 / std::sqrt(a[3]));
    out += line;
  }
  const Eigen::RowVector3d low = model.latent().colwise().minCoeff(), high = model.latent().colwise().maxCoeff();
  std::snprintf(line, sizeof(line), "latent extent: x %.2f..%.2f, y %.2f..%.2f, z %.2f..%.2f\n", low[0], high[0], low[1], high[1], low[2], high[2]);
  out += line;
  out += d.summary.BriefReport() + "\n";
  std::snprintf(line, sizeof(line), "training reconstruction error: %.2f mm (mean over 17 joints, skeleton of %s)\n",
                TrainingReconstructionErrorMm(model), d.skeleton_trial.c_str());
  out += line;
  return out;
}

}  // namespace jgpm
