#include "tracker/filter/body_shape.h"

#include <algorithm>
#include <cmath>

#include "io/base/error.h"

namespace jgpm {

bool BodyShapeOptions::Check(std::string* why) const {
  const char* problem = nullptr;
  if (!(width_probe > 0 && width_probe < 0.5 && length_probe > 0 && length_probe < 0.5))
    problem = "body shape probes must be in (0, 0.5)";
  else if (!(rate >= 0 && rate <= 1)) problem = "body shape rate must be in [0, 1]";
  else if (!(min_width > 0 && min_width <= 1 && max_width >= 1 && min_length > 0 && min_length <= 1 && max_length >= 1))
    problem = "body shape bounds must hold 1";
  else if (!(floor_probe_mm > 0 && max_floor_mm >= 0)) problem = "body shape floor probe must be > 0 and bound >= 0";
  else if (!(garment_probe > 0 && garment_rate >= 0 && garment_rate <= 1 && max_garment >= 0 && garment_drawn >= 0))
    problem = "body shape garment probe must be > 0, its rate in [0, 1], its bound and where it is drawn >= 0";
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

Build BodyShape::drawn() const {
  Build b = build_;
  if (b.garment < options_.garment_drawn) b.garment = 0;
  return b;
}

void BodyShape::Update(const std::function<double(const Build&)>& cost, bool several_views) {
  Update(
      [&cost](const std::vector<Build>& builds) {
        std::vector<double> out;
        for (const Build& b : builds) out.push_back(cost(b));
        return out;
      },
      several_views);
}

void BodyShape::Update(const Costs& costs, bool several_views) {
  if (!options_.enabled || options_.rate == 0) return;
  // Each scale fitted: how to move it in a build by a step in its own units (the scales'
  // logarithm, the floor's millimetres), its probe and bounds.
  struct Scale {
    std::function<double&(Build&)> at;
    bool logarithmic;
    double probe, lo, hi, rate;
  };
  const double rate = options_.rate;
  std::vector<Scale> scales;
  for (int r = 1; r < kNumBodyRegions; ++r)  // the torso is the reference
    scales.push_back({[r](Build& b) -> double& { return b.widths[r]; }, true, std::log1p(options_.width_probe),
                      options_.min_width, options_.max_width, rate});
  if (options_.lengths) {
    for (double Proportions::*limb : {&Proportions::legs, &Proportions::arms})
      scales.push_back({[limb](Build& b) -> double& { return b.lengths.*limb; }, true,
                        std::log1p(options_.length_probe), options_.min_length, options_.max_length, rate});
  }
  if (several_views)
    scales.push_back({[](Build& b) -> double& { return b.floor_mm; }, false, options_.floor_probe_mm,
                      -options_.max_floor_mm, options_.max_floor_mm, rate});
  if (options_.garment)
    scales.push_back({[](Build& b) -> double& { return b.garment; }, false, options_.garment_probe, 0,
                      options_.max_garment, options_.garment_rate});
  const auto moved = [](const Scale& s, Build b, double step) {
    double& v = s.at(b);
    v = s.logarithmic ? v * std::exp(step) : v + step;
    return b;
  };
  std::vector<Build> builds = {build_};
  for (const Scale& s : scales) {
    builds.push_back(moved(s, build_, s.probe));
    builds.push_back(moved(s, build_, -s.probe));
  }
  const std::vector<double> cost = costs(builds);
  JGPM_CHECK(cost.size() == builds.size());
  for (double c : cost)
    if (!std::isfinite(c)) return;
  const double here = cost[0];
  Build next = build_;
  for (size_t k = 0; k < scales.size(); ++k) {
    // The step to the minimum of the parabola through (-h, down), (0, here), (h, up), at
    // most h; h downhill when it has none.
    const double h = scales[k].probe, up = cost[1 + 2 * k], down = cost[2 + 2 * k];
    const double slope = (up - down) / (2 * h), curvature = (up + down - 2 * here) / (h * h);
    const double step = std::clamp(curvature > 0 ? -slope / curvature : (slope > 0 ? -h : slope < 0 ? h : 0), -h, h);
    Build stepped = moved(scales[k], build_, scales[k].rate * step);
    scales[k].at(next) = std::clamp(scales[k].at(stepped), scales[k].lo, scales[k].hi);
  }
  build_ = next;
}

}  // namespace jgpm
