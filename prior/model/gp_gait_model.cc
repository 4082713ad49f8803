#include "prior/model/gp_gait_model.h"

#include <algorithm>
#include <cmath>
#include <future>
#include <vector>

#include <nanoflann.hpp>

#include "io/base/error.h"
#include "prior/numerics/rbf_row.h"

namespace jgpm {
namespace {

void Require(bool condition, const std::string& source, const std::string& what) {
  if (!condition) ThrowInputError(source, "inconsistent model: " + what);
}

// The mapping kernel's log hyper-parameters, checked before the kernel is built from them.
const Eigen::VectorXd& CheckedLogBeta(const GaitModelData& data, const std::string& source) {
  Require(data.params.log_beta.size() == 3 && data.params.log_beta.allFinite(), source,
          "mapping kernel needs 3 finite log hyper-parameters");
  return data.params.log_beta;
}

}  // namespace

struct GpGaitModel::Neighbours {
  explicit Neighbours(const Eigen::MatrixXd& x) : tree(3, std::cref(x)) {}
  nanoflann::KDTreeEigenMatrixAdaptor<Eigen::MatrixXd> tree;
};

GpGaitModel::~GpGaitModel() = default;

GpGaitModel::GpGaitModel(GaitModelData data, const std::string& source)
    : GaitModel(std::move(data), source), kernel_(Kernel::Kind::kRbf, CheckedLogBeta(data_, source)) {
  const GpParameters& p = data_.params;
  Require(p.log_alpha.size() == (data_.terms.dynamics ? 4 : 0) && p.log_alpha.allFinite(), source,
          "dynamics kernel needs 4 finite log hyper-parameters");
  Require(p.log_w.size() == (data_.terms.channel_scales ? NumChannels() : 0) && p.log_w.allFinite(), source,
          "channel scales must be one finite value per channel");
  // The dynamics' kernel is built and factorised on a thread of its own while the mapping's
  // is on this one: they share nothing, and the two factorisations (an 1800-wide one each
  // for the torus prior, one OpenBLAS thread each) were most of a model's load.
  std::future<void> dynamics;
  if (data_.terms.dynamics) dynamics = std::async(std::launch::async, [this, &source] { BuildDynamics(source); });
  if (!chol_.Compute(kernel_.Matrix(p.x))) ThrowInputError(source, "mapping kernel: " + chol_.why());
  a_ = chol_.Solve(data_.set.y);
  if (dynamics.valid()) dynamics.get();  // rethrows the dynamics' error
  Require(a_.allFinite() && b_.allFinite(), source, "the kernels' solutions are not finite");
  neighbours_ = std::make_unique<Neighbours>(p.x);
}

void GpGaitModel::BuildDynamics(const std::string& source) {
  const GpParameters& p = data_.params;
  std::vector<int> in, out;
  const int poses = data_.set.poses_per_gait;
  for (int i = 0; i < NumPoints(); ++i) {
    if ((i + 1) % poses != 0) {
      in.push_back(i);
      out.push_back(i + 1);
    }
  }
  Require(!in.empty(), source, "dynamics need at least 2 poses per gait");
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

void GpGaitModel::Predict(const Eigen::Vector3d& x, Eigen::VectorXd* pose_deg, double* variance) const {
  const Eigen::VectorXd k = kernel_.Cross(data_.params.x, x);
  *pose_deg = Denormalise(a_.transpose() * k);
  if (variance) *variance = std::max(0.0, kernel_.Self(x) - chol_.HalfSolve(k).squaredNorm());
}

double GpGaitModel::LogPrior(const Eigen::Vector3d& x, Eigen::Vector3d* gradient) const {
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
    const Eigen::Vector3d dvariance = 2 * kernel_.inverse_width() * (weights.sum() * x - xs.transpose() * weights);
    *gradient -= 0.5 * d / variance * dvariance;
  }
  return value;
}

Eigen::Map<Eigen::MatrixXd> GpGaitModel::Cross(const Eigen::Ref<const Eigen::MatrixXd>& xs, ModelWorkspace* workspace,
                                               int slot) const {
  const Eigen::MatrixXd& train = data_.params.x;
  Eigen::Map<Eigen::MatrixXd> k = workspace->Block(slot, train.rows(), xs.rows());
  for (int t = 0; t < xs.rows(); ++t) {
    const Eigen::Vector3d q = xs.row(t).transpose();
    RbfRow(train.data(), static_cast<int>(train.rows()), q.data(), kernel_.signal_variance(), kernel_.inverse_width(),
           k.col(t).data());
  }
  return k;
}

void GpGaitModel::MeanPoses(const Eigen::Ref<const Eigen::MatrixXd>& xs, Eigen::Ref<Eigen::MatrixXd> poses_deg,
                            ModelWorkspace* workspace) const {
  CheckBatch(xs, poses_deg.rows(), poses_deg.cols(), xs.rows(), NumChannels());
  const Eigen::Map<Eigen::MatrixXd> k = Cross(xs, workspace, 0);
  poses_deg.noalias() = k.transpose() * a_;
  DenormaliseRows(poses_deg);
}

Eigen::MatrixXd GpGaitModel::MeanPoses(const Eigen::MatrixXd& xs, std::array<Eigen::MatrixXd, 3>* jacobians) const {
  ModelWorkspace workspace;
  Eigen::MatrixXd poses(xs.rows(), NumChannels());
  MeanPoses(xs, poses, &workspace);
  if (jacobians) {
    // dk_ti/dx_td = b2 (x_id - x_td) k_ti, so d pose_t / d x_td = scale o (b2 (k o (x_d - x_td)) A).
    const Eigen::MatrixXd k = workspace.Block(0, NumPoints(), xs.rows()).transpose();  // T x N
    const Eigen::MatrixXd& train = data_.params.x;
    for (int d = 0; d < 3; ++d) {
      const Eigen::MatrixXd kd =
          (k.array().rowwise() * train.col(d).transpose().array()).matrix() - xs.col(d).asDiagonal() * k;
      (*jacobians)[d] = ((kernel_.inverse_width() * kd * a_).array().rowwise() * data_.set.scale.array()).matrix();
    }
  }
  return poses;
}

double GpGaitModel::VarianceBound(const Eigen::Vector3d& x, int neighbours) const {
  const Eigen::MatrixXd& xs = data_.params.x;
  if (neighbours >= NumPoints()) return Variances(x.transpose())[0];
  const int m = std::max(1, neighbours);
  std::vector<Eigen::Index> index(m);
  std::vector<double> distance2(m);
  neighbours_->tree.index->knnSearch(x.data(), m, index.data(), distance2.data());
  Eigen::MatrixXd subset(m, 3);
  for (int i = 0; i < m; ++i) subset.row(i) = xs.row(index[i]);
  // The subset's kernel with the full factor's jitter: more noise than the full model had
  // (the factorisation may add jitter of its own) only raises the bound.
  Eigen::MatrixXd k_ss = kernel_.Matrix(subset);
  k_ss.diagonal().array() += chol_.jitter();
  Cholesky chol;
  if (!chol.Compute(k_ss)) return kernel_.Self(x);  // the prior's variance bounds it too
  return std::max(0.0, kernel_.Self(x) - chol.HalfSolve(kernel_.Cross(subset, x)).squaredNorm());
}

Eigen::VectorXd GpGaitModel::Variances(const Eigen::MatrixXd& xs) const {
  // All points at once: v_j = k** - |L^-1 k_j|^2.
  ModelWorkspace workspace;
  Eigen::Map<Eigen::MatrixXd> k = Cross(xs, &workspace, 0);
  chol_.HalfSolveInPlace(k);
  return (Eigen::VectorXd::Constant(xs.rows(), kernel_.signal_variance()) - k.colwise().squaredNorm().transpose())
      .cwiseMax(0.0);
}

void GpGaitModel::LogPriors(const Eigen::Ref<const Eigen::MatrixXd>& xs, Eigen::Ref<Eigen::VectorXd> out,
                            ModelWorkspace* workspace) const {
  LogDensities(xs, out, workspace);
  Eigen::Map<Eigen::MatrixXd> k = Cross(xs, workspace, 0);
  chol_.HalfSolveInPlace(k);
  const double floor = kernel_.noise_variance();
  const double d = NumChannels();
  for (int t = 0; t < xs.rows(); ++t) {
    const double variance = std::max(floor, kernel_.signal_variance() - k.col(t).squaredNorm());
    out[t] -= 0.5 * d * std::log(variance);
  }
}

void GpGaitModel::NextLatents(const Eigen::Ref<const Eigen::MatrixXd>& xs, Eigen::Ref<Eigen::MatrixXd> next,
                              ModelWorkspace* workspace) const {
  if (!dynamics_) return GaitModel::NextLatents(xs, next, workspace);
  CheckBatch(xs, next.rows(), next.cols(), xs.rows(), 3);
  Eigen::Map<Eigen::MatrixXd> k = workspace->Block(1, x_in_.rows(), xs.rows());
  for (int t = 0; t < xs.rows(); ++t) {
    const Eigen::Vector3d q = xs.row(t).transpose();
    RbfRow(x_in_.data(), static_cast<int>(x_in_.rows()), q.data(), dynamics_->signal_variance(),
           dynamics_->inverse_width(), k.col(t).data());
  }
  k.noalias() += dynamics_->linear_variance() * x_in_ * xs.transpose();
  next.noalias() = k.transpose() * b_;
}

Eigen::Vector3d GpGaitModel::NextLatent(const Eigen::Vector3d& x, double* variance, Eigen::Matrix3d* jacobian) const {
  if (!dynamics_) return GaitModel::NextLatent(x, variance, jacobian);
  const Eigen::VectorXd k = dynamics_->Cross(x_in_, x);
  if (variance) *variance = std::max(0.0, dynamics_->Self(x) - dynamics_chol_.HalfSolve(k).squaredNorm());
  if (jacobian) {
    // k_i = a1 exp(-a2/2 |x - x_i|^2) + a3 x_i.x: dk_i/dx = a2 (x_i - x) rbf_i + a3 x_i.
    const Eigen::VectorXd rbf = k - dynamics_->linear_variance() * x_in_ * x;
    const Eigen::MatrixXd dk =
        dynamics_->inverse_width() * (rbf.asDiagonal() * (x_in_.rowwise() - x.transpose())) +
        dynamics_->linear_variance() * x_in_;  // N x 3
    *jacobian = b_.transpose() * dk;
  }
  return b_.transpose() * k;
}

}  // namespace jgpm
