#include "tracker/state/joint_space_state.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace jgpm {
namespace {

constexpr double kDeg = std::numbers::pi / 180;

double WrapAngle(double a) { return a - 2 * std::numbers::pi * std::floor((a + std::numbers::pi) / (2 * std::numbers::pi)); }

}  // namespace

JointSpaceStateModel::JointSpaceStateModel(const GaitModel& model, bool known_size)
    : known_size_(known_size),
      model_(model),
      channels_(model.NumChannels()),
      placer_(model.skeleton()) {
  const TrainingSet& set = model.data().set;
  const Eigen::MatrixXd& y = set.y_deg;
  mean_ = y.colwise().mean().transpose();
  spread_ = ((y.rowwise() - mean_.transpose()).colwise().squaredNorm() / y.rows()).cwiseSqrt().transpose();
  low_ = y.colwise().minCoeff().transpose().array() - 10;
  high_ = y.colwise().maxCoeff().transpose().array() + 10;
  // Typical change per frame: RMS difference of consecutive poses along the cycles (the
  // cycles close, so the last pose is followed by the first).
  const int poses = set.poses_per_gait;
  step_ = Eigen::VectorXd::Zero(channels_);
  int count = 0;
  for (int start = 0; start + poses <= y.rows(); start += poses) {
    for (int p = 0; p < poses; ++p) {
      step_ += (y.row(start + (p + 1) % poses) - y.row(start + p)).cwiseAbs2().transpose();
      ++count;
    }
  }
  step_ = (step_ / std::max(count, 1)).cwiseSqrt().cwiseMax(0.1);
}

std::vector<std::string> JointSpaceStateModel::CoordinateNames() const { return placer_.layout().channel_names(); }

void JointSpaceStateModel::Sample(const InitialGuess& guess, Random* r, double* s) const {
  for (int c = 0; c < channels_; ++c) {
    s[c] = guess.coordinates.size() == channels_ ? guess.coordinates[c] + 0.5 * step_[c] * r->Normal()
                                                 : mean_[c] + 0.5 * spread_[c] * r->Normal();
  }
  const PlacementIndex p = placement();
  s[p.x] = guess.floor_mm.x() + guess.floor_std_mm * r->Normal();
  s[p.z] = guess.floor_mm.y() + guess.floor_std_mm * r->Normal();
  s[p.heading] =
      guess.heading_std_rad >= std::numbers::pi ? (2 * r->Uniform() - 1) * std::numbers::pi : guess.heading_rad + guess.heading_std_rad * r->Normal();
  s[p.rate] = guess.speed_mm_s >= 0 ? guess.speed_mm_s + 80 * r->Normal() : 1250 + 150 * r->Normal();
  s[p.size] = guess.size + guess.size_std * r->Normal();
  s[p.width] = guess.width + guess.width_std * r->Normal();
  Normalise(s);
}

void JointSpaceStateModel::Predict(double dt, Random* r, double* s) const {
  const double k = std::sqrt(std::max(dt, 0.0) * 30);
  for (int c = 0; c < channels_; ++c) s[c] += k * step_[c] * r->Normal();
  const PlacementIndex p = placement();
  s[p.x] += s[p.rate] * dt * std::sin(s[p.heading]) + k * 8 * r->Normal();
  s[p.z] += s[p.rate] * dt * std::cos(s[p.heading]) + k * 8 * r->Normal();
  s[p.heading] += k * 1.0 * kDeg * r->Normal();
  s[p.rate] += k * 30 * r->Normal();
  s[p.size] += k * 0.001 * r->Normal();
  s[p.width] += k * kWidthNoise * r->Normal();
  Normalise(s);
}

Eigen::VectorXd JointSpaceStateModel::DiffusionStd() const {
  Eigen::VectorXd std(Dimension());
  std.head(channels_) = 2 * step_;
  std.tail(6) << 30, 30, 6 * kDeg, 60, known_size_ ? 0.0 : 0.01, kWidthDiffusion;
  return std;
}

void JointSpaceStateModel::Normalise(double* s) const {
  for (int c = 0; c < channels_; ++c) s[c] = std::clamp(s[c], low_[c], high_[c]);
  const PlacementIndex p = placement();
  s[p.heading] = WrapAngle(s[p.heading]);
  s[p.rate] = std::clamp(s[p.rate], 200.0, 2500.0);
  s[p.size] = known_size_ ? 1.0 : std::clamp(s[p.size], 0.75, 1.3);
  s[p.width] = std::clamp(s[p.width], kMinWidth, kMaxWidth);
}

double JointSpaceStateModel::Period(int dimension) const {
  return dimension == placement().heading ? 2 * std::numbers::pi : 0;
}

double JointSpaceStateModel::Evaluate(const double* s, Eigen::Matrix3Xd* joints) const {
  const PlacementIndex p = placement();
  placer_.Place(s, s[p.x], s[p.z], s[p.heading], s[p.size], joints);
  return 0;
}

Eigen::VectorXd JointSpaceStateModel::Pose(const double* s) const { return Eigen::Map<const Eigen::VectorXd>(s, channels_); }

}  // namespace jgpm
