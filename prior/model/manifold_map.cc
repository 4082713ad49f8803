#include "prior/model/manifold_map.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include <Eigen/Cholesky>

namespace jgpm {

ManifoldMap::ManifoldMap(const TrainingSet& set, const Eigen::MatrixXd& latent, std::vector<int> gait_order,
                         TopologyShape shape)
    : set_(set), latent_(latent), gait_order_(std::move(gait_order)), shape_(shape) {
  layers_by_scale_.resize(set.NumLayers());
  std::iota(layers_by_scale_.begin(), layers_by_scale_.end(), 0);
  std::sort(layers_by_scale_.begin(), layers_by_scale_.end(),
            [&](int a, int b) { return set.layer_scales[a] < set.layer_scales[b]; });
}

Eigen::Vector3d ManifoldMap::LatentAt(int layer, int gait_position, int pose) const {
  return latent_.row(set_.Row(layer, gait_order_[gait_position], pose)).transpose();
}

Eigen::Vector3d ManifoldMap::ToLatent(const ManifoldPoint& point) const {
  const int poses = set_.poses_per_gait, gaits = set_.NumGaits();
  const bool torus = shape_ == TopologyShape::kTorus;
  double p = point.phase * poses;
  p -= poses * std::floor(p / poses);
  const int p0 = static_cast<int>(std::floor(p)) % poses, p1 = (p0 + 1) % poses;
  const double wp = p - std::floor(p);
  double g = point.gait;
  int g0, g1;
  double wg;
  if (torus) {
    g -= gaits * std::floor(g / gaits);
    g0 = static_cast<int>(std::floor(g)) % gaits;
    g1 = (g0 + 1) % gaits;
    wg = g - std::floor(g);
  } else {
    g = std::clamp(g, 0.0, static_cast<double>(gaits - 1));
    g0 = std::min(static_cast<int>(std::floor(g)), gaits - 1);
    g1 = std::min(g0 + 1, gaits - 1);
    wg = g - g0;
  }
  auto in_layer = [&](int layer) -> Eigen::Vector3d {
    return (1 - wg) * ((1 - wp) * LatentAt(layer, g0, p0) + wp * LatentAt(layer, g0, p1)) +
           wg * ((1 - wp) * LatentAt(layer, g1, p0) + wp * LatentAt(layer, g1, p1));
  };
  const std::vector<int>& by_scale = layers_by_scale_;
  const auto scale_of = [&](int k) { return set_.layer_scales[by_scale[k]]; };
  if (by_scale.size() == 1 || point.scale <= scale_of(0)) return in_layer(by_scale.front());
  if (point.scale >= scale_of(static_cast<int>(by_scale.size()) - 1)) return in_layer(by_scale.back());
  int k = 0;
  while (point.scale > scale_of(k + 1)) ++k;
  const double ws = (point.scale - scale_of(k)) / (scale_of(k + 1) - scale_of(k));
  return (1 - ws) * in_layer(by_scale[k]) + ws * in_layer(by_scale[k + 1]);
}

ManifoldPoint ManifoldMap::FromLatent(const Eigen::Vector3d& x) const {
  std::vector<int> position(set_.NumGaits());
  for (int k = 0; k < set_.NumGaits(); ++k) position[gait_order_[k]] = k;
  const auto latent = [&](const Eigen::Vector3d& q) -> Eigen::Vector3d { return ToLatent({q[0], q[1], q[2]}); };
  const double lowest = set_.layer_scales[layers_by_scale_.front()];
  const double highest = set_.layer_scales[layers_by_scale_.back()];
  // The interpolation can fold, so start Gauss-Newton (numeric Jacobian, halving steps
  // that do not help) from the 8 nearest training points and keep the best end.
  const Eigen::VectorXd d2 = (latent_.rowwise() - x.transpose()).rowwise().squaredNorm();
  std::vector<int> order(d2.size());
  std::iota(order.begin(), order.end(), 0);
  const int starts = std::min<int>(8, static_cast<int>(order.size()));
  std::partial_sort(order.begin(), order.begin() + starts, order.end(),
                    [&](int a, int b) { return d2[a] < d2[b]; });
  Eigen::Vector3d best(0, 0, 1);
  double best_error = std::numeric_limits<double>::infinity();
  for (int s = 0; s < starts; ++s) {
    const TrainingPoint& start = set_.points[order[s]];
    Eigen::Vector3d m(static_cast<double>(start.pose) / set_.poses_per_gait, position[start.gait],
                      set_.layer_scales[start.layer]);
    double error = (latent(m) - x).squaredNorm();
    for (int iteration = 0; iteration < 20 && error > 1e-24; ++iteration) {
      const Eigen::Vector3d r = latent(m) - x;
      Eigen::Matrix3d j;
      const double h = 1e-5;
      for (int c = 0; c < 3; ++c) {
        Eigen::Vector3d plus = m, minus = m;
        plus[c] += h;
        minus[c] -= h;
        j.col(c) = (latent(plus) - latent(minus)) / (2 * h);
      }
      Eigen::Vector3d step = (j.transpose() * j + 1e-12 * Eigen::Matrix3d::Identity()).ldlt().solve(-j.transpose() * r);
      if (!step.allFinite()) break;
      bool improved = false;
      for (int halving = 0; halving < 10 && !improved; ++halving, step *= 0.5) {
        Eigen::Vector3d next = m + step;
        next[2] = std::clamp(next[2], lowest, highest);
        const double next_error = (latent(next) - x).squaredNorm();
        if (next_error < error) {
          m = next;
          error = next_error;
          improved = true;
        }
      }
      if (!improved) break;
    }
    if (error < best_error) best_error = error, best = m;
  }
  ManifoldPoint point;
  point.phase = best[0] - std::floor(best[0]);
  point.gait = shape_ == TopologyShape::kTorus ? best[1] - set_.NumGaits() * std::floor(best[1] / set_.NumGaits())
                                              : std::clamp(best[1], 0.0, set_.NumGaits() - 1.0);
  point.scale = best[2];
  return point;
}

}  // namespace jgpm
