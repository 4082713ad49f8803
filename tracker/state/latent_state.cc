#include "tracker/state/latent_state.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace jgpm {
namespace {

constexpr double kDeg = std::numbers::pi / 180;

double WrapAngle(double a) { return a - 2 * std::numbers::pi * std::floor((a + std::numbers::pi) / (2 * std::numbers::pi)); }

}  // namespace

LatentStateModel::LatentStateModel(const GaitModel& model, const PoseTable& table, const LatentDynamics& dynamics)
    : model_(model), table_(table), limbs_(model.skeleton()), d_(dynamics), step_(MeanLatentStep(model)) {}

void LatentStateModel::Sample(const InitialGuess& guess, Random* r, double* s) const {
  if (guess.coordinates.size() == 3) {
    for (int d = 0; d < 3; ++d) s[d] = guess.coordinates[d] + 0.25 * d_.latent_diffusion * step_ * r->Normal();
  } else {
    const Eigen::MatrixXd& x = model_.latent();
    const int i = std::min(static_cast<int>(r->Uniform() * x.rows()), static_cast<int>(x.rows()) - 1);
    for (int d = 0; d < 3; ++d) s[d] = x(i, d) + 0.5 * step_ * r->Normal();
  }
  s[3] = guess.floor_mm.x() + guess.floor_std_mm * r->Normal();
  s[4] = guess.floor_mm.y() + guess.floor_std_mm * r->Normal();
  s[5] = guess.heading_std_rad >= std::numbers::pi ? (2 * r->Uniform() - 1) * std::numbers::pi : guess.heading_rad + guess.heading_std_rad * r->Normal();
  s[6] = guess.speed_mm_s >= 0 ? guess.speed_mm_s + 80 * r->Normal() : 1250 + 150 * r->Normal();
  s[7] = guess.size + guess.size_std * r->Normal();
  s[8] = guess.width + guess.width_std * r->Normal();
  Normalise(s);
}

void LatentStateModel::Predict(double dt, Random* r, double* s) const {
  const double k = std::sqrt(std::max(dt, 0.0) * 30);
  Eigen::Vector3d x(s[0], s[1], s[2]);
  if (model_.HasDynamics()) {
    // One dynamics step per 1/30 s: whole steps, then the fraction of the next.
    const double steps = std::max(dt, 0.0) * kStepsPerSecond;
    const int whole = static_cast<int>(std::floor(steps + 1e-9));
    for (int i = 0; i < whole; ++i) x = model_.NextLatent(x, nullptr);
    const double fraction = steps - whole;
    if (fraction > 1e-9) x += fraction * (model_.NextLatent(x, nullptr) - x);
  }
  for (int d = 0; d < 3; ++d) s[d] = x[d] + k * d_.latent_noise * step_ * r->Normal();
  s[3] += s[6] * dt * std::sin(s[5]) + k * d_.root_noise_mm * r->Normal();
  s[4] += s[6] * dt * std::cos(s[5]) + k * d_.root_noise_mm * r->Normal();
  s[5] += k * (r->Uniform() < d_.turn_share ? d_.turn_noise_deg : d_.heading_noise_deg) * kDeg * r->Normal();
  s[6] += k * d_.speed_noise_mm_s * r->Normal();
  s[7] += k * d_.size_noise * r->Normal();
  s[8] += k * d_.width_noise * r->Normal();
  Normalise(s);
}

Eigen::VectorXd LatentStateModel::DiffusionStd() const {
  Eigen::VectorXd std(9);
  const double latent = d_.latent_diffusion * step_;
  std << latent, latent, latent, d_.root_diffusion_mm, d_.root_diffusion_mm, d_.heading_diffusion_deg * kDeg,
      d_.speed_diffusion_mm_s, d_.size_diffusion, d_.width_diffusion;
  return std;
}

void LatentStateModel::Normalise(double* s) const {
  for (int d = 0; d < 3; ++d) s[d] = std::clamp(s[d], table_.lo()[d], table_.hi()[d]);
  s[5] = WrapAngle(s[5]);
  s[6] = std::clamp(s[6], d_.min_speed_mm_s, d_.max_speed_mm_s);
  s[7] = std::clamp(s[7], d_.min_size, d_.max_size);
  s[8] = std::clamp(s[8], d_.min_width, d_.max_width);
}

double LatentStateModel::Period(int dimension) const { return dimension == 5 ? 2 * std::numbers::pi : 0; }

double LatentStateModel::Evaluate(const double* s, Eigen::Matrix3Xd* joints) const {
  thread_local Eigen::Matrix3Xd relative;
  double foot = 0, log_density = 0;
  table_.Lookup(Eigen::Vector3d(s[0], s[1], s[2]), &relative, &foot, &log_density);
  limbs_.Apply(proportions_, &relative, &foot);
  PlaceInWorld(relative, foot, s[3], s[4], s[5], s[7], kFootClearanceMm + floor_mm_, joints);
  return log_density;
}

Eigen::VectorXd LatentStateModel::Pose(const double* s) const {
  return model_.MeanPoses(Eigen::RowVector3d(s[0], s[1], s[2])).row(0).transpose();
}

}  // namespace jgpm
