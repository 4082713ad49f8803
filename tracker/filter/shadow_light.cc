#include "tracker/filter/shadow_light.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <numbers>

namespace jgpm {

bool ShadowLightOptions::Check(std::string* why) const {
  std::string problem;
  if (every < 1) problem = "every must be >= 1";
  else if (looks < 1) problem = "looks must be >= 1";
  else if (!(min_gain >= 0)) problem = "min_gain must be >= 0";
  else if (idle_after < 1 || idle_every < 1) problem = "idle_after and idle_every must be >= 1";
  if (!problem.empty() && why) *why = problem;
  return problem.empty();
}

ShadowLight::ShadowLight(const ShadowLightOptions& options) : options_(options) { Coarse(); }

Eigen::Vector3d ShadowLight::Direction(double azimuth_deg, double elevation_deg) {
  const double a = azimuth_deg * std::numbers::pi / 180, e = elevation_deg * std::numbers::pi / 180;
  return {std::cos(e) * std::sin(a), std::sin(e), std::cos(e) * std::cos(a)};
}

Eigen::Vector2d ShadowLight::AnglesOf(const Eigen::Vector3d& direction) {
  const Eigen::Vector3d d = direction.normalized();
  const double azimuth = std::atan2(d.x(), d.z()) * 180 / std::numbers::pi;
  return {azimuth < 0 ? azimuth + 360 : azimuth, std::asin(std::clamp(d.y(), -1.0, 1.0)) * 180 / std::numbers::pi};
}

Eigen::Vector2d ShadowLight::Angles() const {
  return light_ ? AnglesOf(*light_) : Eigen::Vector2d::Constant(std::nan(""));
}

void ShadowLight::Coarse() {
  fine_ = false;
  Grid(0, 15, 24, 20, 10, 7);
}

void ShadowLight::Grid(double azimuth0, double azimuth_step, int azimuths, double elevation0, double elevation_step,
                       int elevations) {
  candidates_.clear();
  for (int i = 0; i < azimuths; ++i)
    for (int j = 0; j < elevations; ++j) {
      const double elevation = elevation0 + j * elevation_step;
      if (elevation < 10 || elevation > 85) continue;
      candidates_.emplace_back(azimuth0 + i * azimuth_step, elevation);
    }
  recent_.clear();
  looks_ = 0;
}

bool ShadowLight::Due() {
  if (!options_.enabled || light_) return false;
  const int every = total_looks_ >= options_.idle_after && !fine_ ? options_.idle_every : options_.every;
  return frames_++ % every == 0;
}

void ShadowLight::Look(const CostFunction& cost) {
  std::vector<std::optional<Eigen::Vector3d>> lights(1);
  for (const Eigen::Vector2d& c : candidates_) lights.emplace_back(Direction(c.x(), c.y()));
  const std::vector<double> costs = cost(lights);
  if (costs.size() != lights.size() || !std::isfinite(costs[0])) return;
  std::vector<double> gains(candidates_.size(), 0);
  for (size_t i = 0; i < candidates_.size(); ++i)
    if (std::isfinite(costs[i + 1])) gains[i] = costs[0] - costs[i + 1];
  recent_.push_back(std::move(gains));
  if (static_cast<int>(recent_.size()) > options_.looks) recent_.pop_front();
  ++looks_, ++total_looks_;
  if (looks_ < options_.looks) return;
  std::vector<double> sum(candidates_.size(), 0);
  for (const std::vector<double>& look : recent_)
    for (size_t i = 0; i < look.size(); ++i) sum[i] += look[i];
  const size_t best = std::distance(sum.begin(), std::max_element(sum.begin(), sum.end()));
  if (sum[best] / options_.looks <= options_.min_gain) {
    if (fine_) Coarse();  // the coarse grid's best did not hold: search it all again
    return;
  }
  if (!fine_) {
    const Eigen::Vector2d c = candidates_[best];
    fine_ = true;
    Grid(c.x() - 12, 3, 9, c.y() - 9, 3, 7);
    return;
  }
  light_ = Direction(candidates_[best].x(), candidates_[best].y());
}

}  // namespace jgpm
