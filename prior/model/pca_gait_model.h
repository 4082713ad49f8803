// The linear baseline: y_normalised = basis x, the 3 leading principal components of the
// training poses. Its latent prior is the Gaussian of the training scores; its "variance"
// is the residual variance of the training poses, the same everywhere.
#pragma once

#include "prior/model/gait_model.h"

namespace jgpm {

class PcaGaitModel : public GaitModel {
 public:
  // InputError naming `source` for a basis that is not channels x 3 finite values.
  PcaGaitModel(GaitModelData data, const std::string& source);

  void Predict(const Eigen::Vector3d& x, Eigen::VectorXd* pose_deg, double* variance) const override;
  double LogDensity(const Eigen::Vector3d& x, Eigen::Vector3d* gradient) const override;
  double LogPrior(const Eigen::Vector3d& x, Eigen::Vector3d* gradient) const override;
  Eigen::MatrixXd MeanPoses(const Eigen::MatrixXd& xs, std::array<Eigen::MatrixXd, 3>* jacobians) const override;
  void MeanPoses(const Eigen::Ref<const Eigen::MatrixXd>& xs, Eigen::Ref<Eigen::MatrixXd> poses_deg,
                 ModelWorkspace* workspace) const override;
  void LogDensities(const Eigen::Ref<const Eigen::MatrixXd>& xs, Eigen::Ref<Eigen::VectorXd> out,
                    ModelWorkspace* workspace) const override;
  void LogPriors(const Eigen::Ref<const Eigen::MatrixXd>& xs, Eigen::Ref<Eigen::VectorXd> out,
                 ModelWorkspace* workspace) const override;

 private:
  Eigen::Vector3d score_variance_;
  double residual_variance_ = 0;
};

}  // namespace jgpm
