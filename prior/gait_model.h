// A trained gait model and what the tracker and the evaluation ask of it: the mean pose
// and predictive variance at a latent point, how plausible a latent point is (log p(x|M)
// and its gradient), the GPDM dynamics step, and for the JGPM family the manifold
// coordinates (pose phase, gait, stride scale) <-> latent point.
//
// GaitModelData is everything a model file holds; GaitModel::Create builds the caches
// predictions need. Two variants: the PCA baseline (linear) and the GP models.
#pragma once

#include <array>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "io/gait_pose.h"
#include "io/skeleton.h"
#include "prior/model_kind.h"
#include "prior/objective.h"
#include "prior/topology.h"
#include "prior/training_progress.h"
#include "prior/training_set.h"

namespace jgpm {

// A point on the joint gait-pose manifold.
struct ManifoldPoint {
  double phase = 0;  // along the walking cycle, [0, 1); 0 = the cycles' first pose
  double gait = 0;   // position along the gait manifold, in gaits (torus: wraps at G)
  double scale = 1;  // stride scale (the layers' scales, e.g. 0.4 .. 1.25)
};

struct GaitModelData {
  ModelKind kind = ModelKind::kPca;
  std::string split;                 // dataset the model was trained on
  std::string learning;              // "full", "local" or "closed form"
  uint64_t seed = 1;
  ObjectiveTerms terms;
  TrainingSet set;
  // JGPM family only (empty gait_order otherwise).
  TopologyOptions topology_options;
  std::vector<int> gait_order;
  Eigen::MatrixXd prior_coordinates;
  GpParameters params;               // PCA: x holds the scores, the rest empty
  Eigen::MatrixXd pca_basis;         // PCA only: D x 3, y_normalised ~ x basis^T
  // Reference skeleton for joint positions: a training trial's subject and its ASF text.
  std::string skeleton_trial;
  std::string skeleton_asf;
  TrainingSummary summary;
};

class GaitModel {
 public:
  // Builds the caches. InputError naming `source` when the data are inconsistent (sizes,
  // non-finite numbers, a kernel that cannot be factorised, an unreadable skeleton).
  static std::unique_ptr<GaitModel> Create(GaitModelData data, const std::string& source);
  virtual ~GaitModel() = default;

  const GaitModelData& data() const { return data_; }
  ModelKind kind() const { return data_.kind; }
  int NumChannels() const { return data_.set.NumChannels(); }
  int NumPoints() const { return data_.set.NumPoints(); }
  const Eigen::MatrixXd& latent() const { return data_.params.x; }

  // Mean pose (channels in degrees) at latent point x, and the predictive variance of the
  // latent function (normalised units; 0 on the training data, growing away from it).
  virtual void Predict(const Eigen::Vector3d& x, Eigen::VectorXd* pose_deg,
                       double* variance) const = 0;
  // Predictive variances at many latent points (rows of xs), as Predict gives them.
  virtual Eigen::VectorXd Variances(const Eigen::MatrixXd& xs) const;
  // Mean poses (degrees, T x D) at many latent points (rows of xs, T x 3), as Predict gives
  // them, in one batch. With `jacobians`, also d pose / d x_d for each latent dimension d
  // (each T x D: row t holds the derivatives of pose t).
  virtual Eigen::MatrixXd MeanPoses(const Eigen::MatrixXd& xs,
                                    std::array<Eigen::MatrixXd, 3>* jacobians = nullptr) const = 0;
  // ln of the latent density up to a constant, O(N): a kernel density over the training
  // latent points (width: median nearest-neighbour distance); PCA: the Gaussian of its
  // scores. `gradient` may be null.
  virtual double LogDensity(const Eigen::Vector3d& x, Eigen::Vector3d* gradient) const;
  // ln p(x|M) up to a constant: LogDensity plus, for GP models, -D/2 ln variance(x), which
  // costs O(N^2). `gradient` may be null.
  virtual double LogPrior(const Eigen::Vector3d& x, Eigen::Vector3d* gradient) const = 0;
  // GPDM family: the mean next latent point along the dynamics, its variance (O(N^2)) and
  // its Jacobian d next / d x (O(N)); either may be null. Others: x itself.
  virtual bool HasDynamics() const { return false; }
  virtual Eigen::Vector3d NextLatent(const Eigen::Vector3d& x, double* variance,
                                     Eigen::Matrix3d* jacobian = nullptr) const;

  // JGPM family.
  bool HasManifold() const { return !data_.gait_order.empty(); }
  // Interpolates the learned latent points over (pose, gait position, layer): periodic in
  // phase, periodic in gait on a torus and clamped to the ends on a cylinder, linear in
  // scale between layers and clamped outside them.
  Eigen::Vector3d ManifoldToLatent(const ManifoldPoint& point) const;
  // The manifold point whose latent point is nearest x (nearest training point, then
  // Gauss-Newton on the interpolation).
  ManifoldPoint LatentToManifold(const Eigen::Vector3d& x) const;

  // Joint positions (mm, 3 x 17 measured joints) of a pose on the reference skeleton.
  const Skeleton& skeleton() const { return skeleton_; }
  void JointPositions(const Eigen::VectorXd& pose_deg, Eigen::Matrix3Xd* joints) const;

 protected:
  GaitModel(GaitModelData data, const std::string& source);
  Eigen::VectorXd Denormalise(const Eigen::VectorXd& y) const;

  GaitModelData data_;
  Skeleton skeleton_;
  std::unique_ptr<GaitPoseKinematics> kinematics_;
  double density_width_ = 1.0;

 private:
  Eigen::Vector3d LatentAt(int layer, int gait_position, int pose) const;
  std::vector<int> layers_by_scale_;
};

// Mean 3-D joint position error (mm, over the 17 measured joints on the reference
// skeleton) between each training pose and the model's mean pose at its latent point: how
// well the model reproduces what it was trained on.
double TrainingReconstructionErrorMm(const GaitModel& model);

// A few lines describing a model: kind, data, hyper-parameters, training summary, latent
// extent and training reconstruction error.
std::string DescribeModel(const GaitModel& model);

}  // namespace jgpm
