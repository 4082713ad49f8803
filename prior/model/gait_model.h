// A trained gait model and what the tracker and the evaluation ask of it: the mean pose
// and predictive variance at a latent point, how plausible a latent point is (log p(x|M)
// and its gradient), the GPDM dynamics step, and for the JGPM family the manifold
// coordinates (pose phase, gait, stride scale) <-> latent point.
//
// GaitModelData is everything a model file holds; GaitModel::Create checks it and builds
// the caches predictions need. Variants: the PCA baseline (prior/model/pca_gait_model.h) and the
// GP models (prior/model/gp_gait_model.h).
//
// Every method is const and thread-safe. The batched calls take many latent points at
// once (rows of a column-major T x 3 matrix) and a ModelWorkspace the caller owns, one
// per thread: after the workspace has grown to the largest batch, they allocate nothing.
#pragma once

#include <array>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "io/gait/gait_pose.h"
#include "io/mocap/skeleton.h"
#include "prior/learning/objective.h"
#include "prior/learning/topology.h"
#include "prior/learning/training_progress.h"
#include "prior/learning/training_set.h"
#include "prior/model/latent_density.h"
#include "prior/model/manifold_map.h"
#include "prior/model/model_kind.h"

namespace jgpm {

struct GaitModelData {
  ModelKind kind = ModelKind::kPca;
  std::string split;                 // dataset the model was trained on
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

// Scratch memory for the batched calls. Not thread-safe itself: one per thread.
class ModelWorkspace {
 public:
  // A rows x cols column-major block over scratch buffer `slot` (0-2), which grows when
  // needed and never shrinks; its contents are undefined.
  Eigen::Map<Eigen::MatrixXd> Block(int slot, Eigen::Index rows, Eigen::Index cols);

 private:
  std::array<std::vector<double>, 3> buffers_;
};

class GaitModel {
 public:
  // Checks the data and builds the caches. InputError naming `source` when the data are
  // inconsistent (sizes, indices, non-finite numbers, a kernel that cannot be factorised,
  // an unreadable skeleton): a model file can never abort the process.
  static std::unique_ptr<GaitModel> Create(GaitModelData data, const std::string& source);
  virtual ~GaitModel();
  GaitModel(const GaitModel&) = delete;
  GaitModel& operator=(const GaitModel&) = delete;

  const GaitModelData& data() const { return data_; }
  ModelKind kind() const { return data_.kind; }
  int NumChannels() const { return data_.set.NumChannels(); }
  int NumPoints() const { return data_.set.NumPoints(); }
  const Eigen::MatrixXd& latent() const { return data_.params.x; }

  // --- One latent point.
  // Mean pose (channels in degrees) at latent point x, and the predictive variance of the
  // latent function (normalised units; 0 on the training data, growing away from it).
  virtual void Predict(const Eigen::Vector3d& x, Eigen::VectorXd* pose_deg, double* variance) const = 0;
  // ln of the latent density up to a constant, O(N): a kernel density over the training
  // latent points (prior/model/latent_density.h); PCA: the Gaussian of its scores. `gradient`
  // may be null.
  virtual double LogDensity(const Eigen::Vector3d& x, Eigen::Vector3d* gradient) const;
  // ln p(x|M) up to a constant: LogDensity plus, for GP models, -D/2 ln variance(x), which
  // costs O(N^2). `gradient` may be null.
  virtual double LogPrior(const Eigen::Vector3d& x, Eigen::Vector3d* gradient) const = 0;
  // GPDM family: the mean next latent point along the dynamics, its variance (O(N^2)) and
  // its Jacobian d next / d x (O(N)); either may be null. Others: x itself.
  virtual bool HasDynamics() const { return false; }
  virtual Eigen::Vector3d NextLatent(const Eigen::Vector3d& x, double* variance,
                                     Eigen::Matrix3d* jacobian = nullptr) const;

  // --- Batches: xs is T x 3 (column-major), outputs are sized by the caller.
  // Mean poses, degrees: `poses_deg` is T x D.
  virtual void MeanPoses(const Eigen::Ref<const Eigen::MatrixXd>& xs, Eigen::Ref<Eigen::MatrixXd> poses_deg,
                         ModelWorkspace* workspace) const = 0;
  // LogDensity of each point: `out` has T entries.
  virtual void LogDensities(const Eigen::Ref<const Eigen::MatrixXd>& xs, Eigen::Ref<Eigen::VectorXd> out,
                            ModelWorkspace* workspace) const;
  // LogPrior of each point (GP models: O(N^2) each).
  virtual void LogPriors(const Eigen::Ref<const Eigen::MatrixXd>& xs, Eigen::Ref<Eigen::VectorXd> out,
                         ModelWorkspace* workspace) const = 0;
  // NextLatent of each point: `next` is T x 3.
  virtual void NextLatents(const Eigen::Ref<const Eigen::MatrixXd>& xs, Eigen::Ref<Eigen::MatrixXd> next,
                           ModelWorkspace* workspace) const;

  // Conveniences over the batches (they allocate). Predictive variances of the rows of xs.
  virtual Eigen::VectorXd Variances(const Eigen::MatrixXd& xs) const;
  // An upper bound on Predict's variance at x, cheap where the exact one is O(N^2): GP
  // models condition on the `neighbours` training points nearest to x alone (a GP
  // conditioned on fewer observations never has a lower variance), O(neighbours^3); equal
  // to the exact variance when neighbours >= N, and for the other models.
  virtual double VarianceBound(const Eigen::Vector3d& x, int neighbours) const;
  // Mean poses (T x D) of the rows of xs; with `jacobians`, also d pose / d x_d for each
  // latent dimension d (each T x D: row t holds the derivatives of pose t).
  virtual Eigen::MatrixXd MeanPoses(const Eigen::MatrixXd& xs,
                                    std::array<Eigen::MatrixXd, 3>* jacobians = nullptr) const = 0;

  // --- JGPM family (prior/model/manifold_map.h).
  bool HasManifold() const { return manifold_.has_value(); }
  Eigen::Vector3d ManifoldToLatent(const ManifoldPoint& point) const;
  ManifoldPoint LatentToManifold(const Eigen::Vector3d& x) const;

  // Joint positions (mm, 3 x 17 measured joints) of a pose on the reference skeleton.
  const Skeleton& skeleton() const { return skeleton_; }
  void JointPositions(const Eigen::VectorXd& pose_deg, Eigen::Matrix3Xd* joints) const;

 protected:
  // Checks everything but the variant's own parameters (InputError naming `source`).
  GaitModel(GaitModelData data, const std::string& source);
  Eigen::VectorXd Denormalise(const Eigen::VectorXd& y) const;
  // Rows of normalised poses -> degrees, in place.
  void DenormaliseRows(Eigen::Ref<Eigen::MatrixXd> y) const;
  static void CheckBatch(const Eigen::Ref<const Eigen::MatrixXd>& xs, Eigen::Index out_rows, Eigen::Index out_cols,
                         Eigen::Index rows, Eigen::Index cols);

  GaitModelData data_;
  Skeleton skeleton_;
  std::unique_ptr<GaitPoseKinematics> kinematics_;
  std::optional<LatentDensity> density_;
  std::optional<ManifoldMap> manifold_;  // points into data_
};

// The mean distance between consecutive training latent points of a gait cycle: the
// latent space's natural step, so that tolerances mean the same for every model's scale.
double MeanLatentStep(const GaitModel& model);

}  // namespace jgpm
