#include "prior/model/pca_gait_model.h"

#include "io/base/error.h"

namespace jgpm {

PcaGaitModel::PcaGaitModel(GaitModelData data, const std::string& source) : GaitModel(std::move(data), source) {
  const int d = NumChannels();
  if (!(data_.pca_basis.rows() == d && data_.pca_basis.cols() == 3 && data_.pca_basis.allFinite())) {
    ThrowInputError(source, "inconsistent model: PCA basis must be channels x 3 finite values");
  }
  score_variance_ = (data_.params.x.colwise().squaredNorm() / NumPoints()).transpose();
  score_variance_ = score_variance_.cwiseMax(1e-12);
  const Eigen::MatrixXd residual = data_.set.y - data_.params.x * data_.pca_basis.transpose();
  residual_variance_ = residual.squaredNorm() / residual.size();
}

void PcaGaitModel::Predict(const Eigen::Vector3d& x, Eigen::VectorXd* pose_deg, double* variance) const {
  *pose_deg = Denormalise(data_.pca_basis * x);
  if (variance) *variance = residual_variance_;
}

Eigen::MatrixXd PcaGaitModel::MeanPoses(const Eigen::MatrixXd& xs, std::array<Eigen::MatrixXd, 3>* jacobians) const {
  const TrainingSet& s = data_.set;
  if (jacobians) {
    for (int d = 0; d < 3; ++d) {
      (*jacobians)[d] = (data_.pca_basis.col(d).transpose().cwiseProduct(s.scale)).replicate(xs.rows(), 1);
    }
  }
  return ((xs * data_.pca_basis.transpose()).array().rowwise() * s.scale.array()).rowwise() + s.mean.array();
}

void PcaGaitModel::MeanPoses(const Eigen::Ref<const Eigen::MatrixXd>& xs, Eigen::Ref<Eigen::MatrixXd> poses_deg,
                             ModelWorkspace*) const {
  CheckBatch(xs, poses_deg.rows(), poses_deg.cols(), xs.rows(), NumChannels());
  poses_deg.noalias() = xs * data_.pca_basis.transpose();
  DenormaliseRows(poses_deg);
}

double PcaGaitModel::LogDensity(const Eigen::Vector3d& x, Eigen::Vector3d* gradient) const {
  if (gradient) *gradient = -x.cwiseQuotient(score_variance_);
  return -0.5 * x.cwiseAbs2().cwiseQuotient(score_variance_).sum();
}

double PcaGaitModel::LogPrior(const Eigen::Vector3d& x, Eigen::Vector3d* gradient) const {
  return LogDensity(x, gradient);
}

void PcaGaitModel::LogDensities(const Eigen::Ref<const Eigen::MatrixXd>& xs, Eigen::Ref<Eigen::VectorXd> out,
                                ModelWorkspace*) const {
  CheckBatch(xs, out.rows(), out.cols(), xs.rows(), 1);
  for (int t = 0; t < xs.rows(); ++t) out[t] = LogDensity(xs.row(t).transpose(), nullptr);
}

void PcaGaitModel::LogPriors(const Eigen::Ref<const Eigen::MatrixXd>& xs, Eigen::Ref<Eigen::VectorXd> out,
                             ModelWorkspace* workspace) const {
  LogDensities(xs, out, workspace);
}

}  // namespace jgpm
