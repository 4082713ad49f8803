#include "prior/model/gait_model.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "io/base/error.h"
#include "io/mocap/asf.h"
#include "prior/model/gp_gait_model.h"
#include "prior/model/pca_gait_model.h"

namespace jgpm {
namespace {

void Require(bool condition, const std::string& source, const std::string& what) {
  if (!condition) ThrowInputError(source, "inconsistent model: " + what);
}

// Model files are read from outside: bound the sizes before anything is allocated.
constexpr int64_t kMaxPoints = 1000000, kMaxChannels = 10000;

}  // namespace

Eigen::Map<Eigen::MatrixXd> ModelWorkspace::Block(int slot, Eigen::Index rows, Eigen::Index cols) {
  JGPM_CHECK(slot >= 0 && slot < static_cast<int>(buffers_.size()) && rows >= 0 && cols >= 0);
  std::vector<double>& buffer = buffers_[slot];
  const size_t size = static_cast<size_t>(rows) * static_cast<size_t>(cols);
  if (buffer.size() < size) buffer.resize(size);
  return Eigen::Map<Eigen::MatrixXd>(buffer.data(), rows, cols);
}

std::unique_ptr<GaitModel> GaitModel::Create(GaitModelData data, const std::string& source) {
  if (data.kind == ModelKind::kPca) return std::make_unique<PcaGaitModel>(std::move(data), source);
  return std::make_unique<GpGaitModel>(std::move(data), source);
}

GaitModel::GaitModel(GaitModelData data, const std::string& source) : data_(std::move(data)) {
  TrainingSet& set = data_.set;
  const int64_t d = static_cast<int64_t>(set.channel_names.size());
  Require(d > 0 && d <= kMaxChannels && static_cast<int64_t>(set.channel_joints.size()) == d, source,
          "channel names and joints differ in number");
  Require(set.poses_per_gait > 0 && set.NumGaits() > 0 && set.NumLayers() > 0, source, "no training poses");
  const int64_t n64 = static_cast<int64_t>(set.NumLayers()) * set.NumGaits() * set.poses_per_gait;
  Require(n64 <= kMaxPoints, source, "more than " + std::to_string(kMaxPoints) + " training points");
  const int n = static_cast<int>(n64);
  Require(n >= 2, source, "at least 2 training points needed");
  for (double scale : set.layer_scales) {
    Require(std::isfinite(scale) && scale > 0, source, "layer scales must be finite and > 0");
  }
  Require(set.y_deg.rows() == n && set.y_deg.cols() == d && set.y_deg.allFinite(), source,
          "training poses must be " + std::to_string(n) + " x " + std::to_string(d) + " finite values");
  Require(set.mean.size() == d && set.scale.size() == d && set.mean.allFinite() && set.scale.allFinite() &&
              (set.scale.array() > 0).all(),
          source, "channel means and positive scales needed");
  ComputeDerivedFields(&set);
  Require(data_.params.x.rows() == n && data_.params.x.cols() == 3 && data_.params.x.allFinite(), source,
          "latent points must be " + std::to_string(n) + " x 3 finite values");
  if (!data_.gait_order.empty()) {
    std::vector<int> sorted = data_.gait_order;
    std::sort(sorted.begin(), sorted.end());
    std::vector<int> expected(set.NumGaits());
    std::iota(expected.begin(), expected.end(), 0);
    Require(sorted == expected, source, "gait order must be a permutation of the gaits");
    Require(data_.prior_coordinates.rows() == n && data_.prior_coordinates.cols() == 3 &&
                data_.prior_coordinates.allFinite(),
            source, "prior coordinates must be one row of 3 finite values per training point");
    std::string why;
    if (!data_.topology_options.Check(&why)) Require(false, source, "topology: " + why);
  }
  skeleton_ = ParseAsf(data_.skeleton_asf, source + " (embedded skeleton of " + data_.skeleton_trial + ")");
  kinematics_ = std::make_unique<GaitPoseKinematics>(skeleton_, source);
  const GaitPoseLayout& layout = kinematics_->layout();
  Require(layout.channel_names() == set.channel_names, source, "the skeleton's gait channels differ from the model's");
  // Validation looks joints up by these indices: they must be the skeleton's own.
  Require(layout.channel_joints() == set.channel_joints, source,
          "channel_joints differ from the gait joints of the skeleton's channels");
  density_.emplace(data_.params.x);
  if (!data_.gait_order.empty()) {
    manifold_.emplace(set, data_.params.x, data_.gait_order, data_.topology_options.shape);
  }
}

GaitModel::~GaitModel() = default;

void GaitModel::CheckBatch(const Eigen::Ref<const Eigen::MatrixXd>& xs, Eigen::Index out_rows,
                           Eigen::Index out_cols, Eigen::Index rows, Eigen::Index cols) {
  JGPM_CHECK(xs.cols() == 3 && out_rows == xs.rows() && rows == xs.rows() && out_cols == cols);
}

Eigen::VectorXd GaitModel::Variances(const Eigen::MatrixXd& xs) const {
  Eigen::VectorXd variances(xs.rows());
  Eigen::VectorXd pose;
  for (int i = 0; i < xs.rows(); ++i) Predict(xs.row(i).transpose(), &pose, &variances[i]);
  return variances;
}

double GaitModel::VarianceBound(const Eigen::Vector3d& x, int) const {
  Eigen::VectorXd pose;
  double variance = 0;
  Predict(x, &pose, &variance);
  return variance;
}

Eigen::Vector3d GaitModel::NextLatent(const Eigen::Vector3d& x, double* variance, Eigen::Matrix3d* jacobian) const {
  if (variance) *variance = 0;
  if (jacobian) jacobian->setIdentity();
  return x;
}

void GaitModel::NextLatents(const Eigen::Ref<const Eigen::MatrixXd>& xs, Eigen::Ref<Eigen::MatrixXd> next,
                            ModelWorkspace*) const {
  CheckBatch(xs, next.rows(), next.cols(), xs.rows(), 3);
  next = xs;
}

double GaitModel::LogDensity(const Eigen::Vector3d& x, Eigen::Vector3d* gradient) const {
  return density_->LogDensity(x, gradient);
}

void GaitModel::LogDensities(const Eigen::Ref<const Eigen::MatrixXd>& xs, Eigen::Ref<Eigen::VectorXd> out,
                             ModelWorkspace* workspace) const {
  CheckBatch(xs, out.rows(), out.cols(), xs.rows(), 1);
  Eigen::Map<Eigen::MatrixXd> distances2 = workspace->Block(2, NumPoints(), 1);
  for (int t = 0; t < xs.rows(); ++t) out[t] = density_->LogDensity(xs.row(t).transpose(), distances2.col(0));
}

Eigen::VectorXd GaitModel::Denormalise(const Eigen::VectorXd& y) const {
  return data_.set.mean.transpose() + data_.set.scale.transpose().cwiseProduct(y);
}

void GaitModel::DenormaliseRows(Eigen::Ref<Eigen::MatrixXd> y) const {
  y = (y.array().rowwise() * data_.set.scale.array()).rowwise() + data_.set.mean.array();
}

void GaitModel::JointPositions(const Eigen::VectorXd& pose_deg, Eigen::Matrix3Xd* joints) const {
  JGPM_CHECK(pose_deg.size() == NumChannels());
  kinematics_->Compute(pose_deg.data(), joints);
}

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

Eigen::Vector3d GaitModel::ManifoldToLatent(const ManifoldPoint& point) const {
  JGPM_CHECK(HasManifold());
  return manifold_->ToLatent(point);
}

ManifoldPoint GaitModel::LatentToManifold(const Eigen::Vector3d& x) const {
  JGPM_CHECK(HasManifold());
  return manifold_->FromLatent(x);
}

}  // namespace jgpm
