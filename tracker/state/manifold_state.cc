#include "tracker/state/manifold_state.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "io/base/error.h"

namespace jgpm {
namespace {

constexpr double kDeg = std::numbers::pi / 180;

double Wrap(double value, double period) { return value - period * std::floor(value / period); }
double WrapAngle(double a) { return Wrap(a + std::numbers::pi, 2 * std::numbers::pi) - std::numbers::pi; }

}  // namespace

ManifoldStateModel::ManifoldStateModel(const GaitModel& model, const PoseTable& table, const ManifoldDynamics& dynamics)
    : model_(model), table_(table), limbs_(model.skeleton()), d_(dynamics) {
  if (!model.HasManifold() || !table.manifold()) {
    ThrowInputError("model " + std::string(ModelKindName(model.kind())),
                    "has no gait manifold (the JGPM family has); track it in its latent space");
  }
}

void ManifoldStateModel::Sample(const InitialGuess& guess, Random* r, double* s) const {
  if (guess.coordinates.size() == 3) {
    s[0] = guess.coordinates[0] + 0.25 * d_.phase_diffusion * r->Normal();
    s[1] = guess.coordinates[1] + 0.25 * d_.gait_diffusion * r->Normal();
    s[2] = guess.coordinates[2] + 0.25 * d_.scale_diffusion * r->Normal();
  } else {
    s[0] = r->Uniform();
    s[1] = table_.lo()[1] + r->Uniform() * (table_.hi()[1] - table_.lo()[1]);
    s[2] = d_.start_scale_std > 0 ? 1 + d_.start_scale_std * r->Normal()
                                  : table_.lo()[2] + r->Uniform() * (table_.hi()[2] - table_.lo()[2]);
  }
  s[3] = guess.floor_mm.x() + guess.floor_std_mm * r->Normal();
  s[4] = guess.floor_mm.y() + guess.floor_std_mm * r->Normal();
  s[5] = guess.heading_std_rad >= std::numbers::pi ? (2 * r->Uniform() - 1) * std::numbers::pi : guess.heading_rad + guess.heading_std_rad * r->Normal();
  s[7] = guess.size + guess.size_std * r->Normal();
  s[8] = guess.width + guess.width_std * r->Normal();
  s[6] = 1;  // a placeholder for Normalise, which reads every coordinate; set below
  Normalise(s);
  // A walker covers a stride per cycle: the speed seen at the start sets each particle's
  // cadence for its own stride, so its root keeps pace from the first frame.
  const double stride = table_.StrideMm(s[1], s[2]) * s[7];
  s[6] = guess.speed_mm_s >= 0 && stride > 100 ? guess.speed_mm_s / stride * (1 + 0.05 * r->Normal())
                                                : 0.95 + 0.1 * r->Normal();
  Normalise(s);
}

void ManifoldStateModel::Predict(double dt, Random* r, double* s) const {
  const double k = std::sqrt(std::max(dt, 0.0) * 30);
  const double speed = table_.StrideMm(s[1], s[2]) * s[7] * s[6];  // mm/s
  s[0] += s[6] * dt + k * d_.phase_noise * r->Normal();
  s[1] += k * d_.gait_noise * r->Normal();
  s[2] += k * d_.scale_noise * r->Normal();
  s[3] += speed * dt * std::sin(s[5]) + k * d_.root_noise_mm * r->Normal();
  s[4] += speed * dt * std::cos(s[5]) + k * d_.root_noise_mm * r->Normal();
  s[5] += k * (r->Uniform() < d_.turn_share ? d_.turn_noise_deg : d_.heading_noise_deg) * kDeg * r->Normal();
  s[6] += k * d_.cadence_noise * r->Normal();
  s[7] += k * d_.size_noise * r->Normal();
  s[8] += k * d_.width_noise * r->Normal();
  Normalise(s);
}

void ManifoldStateModel::Pace(double speed_mm_s, double share, double* s, bool cover) const {
  const double stride = table_.StrideMm(s[1], s[2]) * s[7];
  if (!(stride > 0) || !(speed_mm_s >= 0)) return;
  // On the cadence's size, its sign apart: to a stop, s[6] + (0 - s[6]) is +0 either way.
  const double size = std::abs(s[6]);
  const double target = cover || speed_mm_s < d_.stop_speed_mm_s ? speed_mm_s / stride
                                                                  : std::max(size, d_.walking_min_cadence);
  s[6] = std::copysign(size + std::clamp(share, 0.0, 1.0) * (target - size), s[6]);
  Normalise(s);
}

Eigen::VectorXd ManifoldStateModel::DiffusionStd() const {
  Eigen::VectorXd std(9);
  std << d_.phase_diffusion, d_.gait_diffusion, d_.scale_diffusion, d_.root_diffusion_mm, d_.root_diffusion_mm,
      d_.heading_diffusion_deg * kDeg, d_.cadence_diffusion, d_.size_diffusion, d_.width_diffusion;
  return std;
}

void ManifoldStateModel::Normalise(double* s) const {
  s[0] = Wrap(s[0], 1.0);
  s[1] = table_.periodic(1) ? Wrap(s[1], table_.hi()[1]) : std::clamp(s[1], table_.lo()[1], table_.hi()[1]);
  s[2] = std::clamp(s[2], table_.lo()[2], table_.hi()[2]);
  s[5] = WrapAngle(s[5]);
  s[6] = std::copysign(std::clamp(std::abs(s[6]), d_.min_cadence, d_.max_cadence), s[6]);
  s[7] = std::clamp(s[7], d_.min_size, d_.max_size);
  s[8] = std::clamp(s[8], d_.min_width, d_.max_width);
}

double ManifoldStateModel::Period(int dimension) const {
  if (dimension == 0) return 1.0;
  if (dimension == 1 && table_.periodic(1)) return table_.hi()[1];
  if (dimension == 5) return 2 * std::numbers::pi;
  return 0;
}

double ManifoldStateModel::Evaluate(const double* s, Eigen::Matrix3Xd* joints) const {
  thread_local Eigen::Matrix3Xd relative;
  double foot = 0, log_density = 0;
  table_.Lookup(Eigen::Vector3d(s[0], s[1], s[2]), &relative, &foot, &log_density);
  limbs_.Apply(proportions_, &relative, &foot);
  PlaceInWorld(relative, foot, s[3], s[4], s[5], s[7], kFootClearanceMm + floor_mm_, joints);
  return log_density;
}

Eigen::VectorXd ManifoldStateModel::Pose(const double* s) const {
  return model_.MeanPoses(model_.ManifoldToLatent({s[0], s[1], s[2]}).transpose()).row(0).transpose();
}

}  // namespace jgpm
