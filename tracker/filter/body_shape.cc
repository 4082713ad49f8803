#include "tracker/filter/body_shape.h"

#include <algorithm>
#include <cmath>

namespace jgpm {

bool BodyShapeOptions::Check(std::string* why) const {
  const char* problem = nullptr;
  if (!(width_probe > 0 && width_probe < 0.5 && length_probe > 0 && length_probe < 0.5))
    problem = "body shape probes must be in (0, 0.5)";
  else if (!(rate >= 0 && rate <= 1)) problem = "body shape rate must be in [0, 1]";
  else if (!(min_width > 0 && min_width <= 1 && max_width >= 1 && min_length > 0 && min_length <= 1 && max_length >= 1))
    problem = "body shape bounds must hold 1";
  else if (!(floor_probe_mm > 0 && max_floor_mm >= 0)) problem = "body shape floor probe must be > 0 and bound >= 0";
  if (problem && why) *why = problem;
  return problem == nullptr;
}

double ShapeCost(const std::vector<CameraScore>& scores) {
  double sum = 0;
  for (const CameraScore& c : scores) {
    if (c.observed_px == 0) continue;  // no one seen: nothing to compare the build with
    sum += static_cast<double>(c.model_px + c.observed_px - 2 * c.overlap_px) / c.observed_px;
  }
  return sum;
}

BodyShape::BodyShape(const BodyShapeOptions& options) : options_(options) {}

void BodyShape::Reset() { build_ = Build(); }

void BodyShape::Update(const std::function<double(const Build&)>& cost, bool several_views) {
  if (!options_.enabled || options_.rate == 0) return;
  const double here = cost(build_);
  if (!std::isfinite(here)) return;
  // The step to the minimum of the parabola through (-h, down), (0, here), (h, up), at
  // most h; h downhill when it has none.
  const auto step = [&](double down, double up, double h) {
    const double slope = (up - down) / (2 * h), curvature = (up + down - 2 * here) / (h * h);
    return std::clamp(curvature > 0 ? -slope / curvature : (slope > 0 ? -h : slope < 0 ? h : 0), -h, h);
  };
  // A scale: where it is in a build, its probe and bounds; fitted in its logarithm.
  const auto fit = [&](const Build& from, auto&& at, double probe, double lo, double hi, Build* to) {
    const double h = std::log1p(probe);
    Build larger = from, smaller = from;
    at(larger) *= std::exp(h);
    at(smaller) *= std::exp(-h);
    const double up = cost(larger), down = cost(smaller);
    if (!std::isfinite(up) || !std::isfinite(down)) return false;
    at(*to) = std::clamp(at(*to) * std::exp(options_.rate * step(down, up, h)), lo, hi);
    return true;
  };
  Build next = build_;
  for (int r = 1; r < kNumBodyRegions; ++r) {  // the torso is the reference
    if (!fit(build_, [r](Build& b) -> double& { return b.widths[r]; }, options_.width_probe, options_.min_width,
             options_.max_width, &next))
      return;
  }
  for (double Proportions::*limb : {&Proportions::legs, &Proportions::arms}) {
    if (!options_.lengths) break;
    if (!fit(build_, [limb](Build& b) -> double& { return b.lengths.*limb; }, options_.length_probe,
             options_.min_length, options_.max_length, &next))
      return;
  }
  if (several_views) {
    const double h = options_.floor_probe_mm;
    Build higher = build_, lower = build_;
    higher.floor_mm += h;
    lower.floor_mm -= h;
    const double up = cost(higher), down = cost(lower);
    if (!std::isfinite(up) || !std::isfinite(down)) return;
    next.floor_mm = std::clamp(build_.floor_mm + options_.rate * step(down, up, h), -options_.max_floor_mm,
                               options_.max_floor_mm);
  }
  build_ = next;
}

}  // namespace jgpm
