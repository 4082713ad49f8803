// The Gaussian-process gait models (GPLVM, GPDM and its variants, the JGPM family): the
// mean pose is Y^T K^-1 k(x) (the channel scales W cancel out of it), the variance
// k(x, x) - k(x)^T K^-1 k(x) by a triangular solve against K's Cholesky factor, and for the
// GPDM family the dynamics GP's mean next latent point.
#pragma once

#include <memory>

#include "prior/model/gait_model.h"
#include "prior/numerics/cholesky.h"
#include "prior/numerics/kernel.h"

namespace jgpm {

class GpGaitModel : public GaitModel {
 public:
  // InputError naming `source` for hyper-parameters of the wrong number or non-finite,
  // or kernels that cannot be factorised.
  GpGaitModel(GaitModelData data, const std::string& source);
  ~GpGaitModel() override;

  void Predict(const Eigen::Vector3d& x, Eigen::VectorXd* pose_deg, double* variance) const override;
  double LogPrior(const Eigen::Vector3d& x, Eigen::Vector3d* gradient) const override;
  bool HasDynamics() const override { return dynamics_ != nullptr; }
  Eigen::Vector3d NextLatent(const Eigen::Vector3d& x, double* variance, Eigen::Matrix3d* jacobian) const override;

  void MeanPoses(const Eigen::Ref<const Eigen::MatrixXd>& xs, Eigen::Ref<Eigen::MatrixXd> poses_deg,
                 ModelWorkspace* workspace) const override;
  void LogPriors(const Eigen::Ref<const Eigen::MatrixXd>& xs, Eigen::Ref<Eigen::VectorXd> out,
                 ModelWorkspace* workspace) const override;
  void NextLatents(const Eigen::Ref<const Eigen::MatrixXd>& xs, Eigen::Ref<Eigen::MatrixXd> next,
                   ModelWorkspace* workspace) const override;
  Eigen::VectorXd Variances(const Eigen::MatrixXd& xs) const override;
  double VarianceBound(const Eigen::Vector3d& x, int neighbours) const override;
  Eigen::MatrixXd MeanPoses(const Eigen::MatrixXd& xs, std::array<Eigen::MatrixXd, 3>* jacobians) const override;

 private:
  // k(x_i, x*_t) for every training point x_i and row x*_t of xs, into workspace slot
  // `slot`: N x T.
  Eigen::Map<Eigen::MatrixXd> Cross(const Eigen::Ref<const Eigen::MatrixXd>& xs, ModelWorkspace* workspace,
                                    int slot) const;
  // The dynamics GP (x_in_, dynamics_, dynamics_chol_, b_) from the training latents;
  // InputError naming `source`.
  void BuildDynamics(const std::string& source);

  Kernel kernel_;
  Cholesky chol_;
  struct Neighbours;  // a k-d tree over the latent points (nanoflann)
  std::unique_ptr<Neighbours> neighbours_;
  Eigen::MatrixXd a_;  // K^-1 Y
  std::unique_ptr<Kernel> dynamics_;
  Cholesky dynamics_chol_;
  Eigen::MatrixXd x_in_, b_;  // dynamics inputs, K_X^-1 X_out
};

}  // namespace jgpm
