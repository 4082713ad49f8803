// Walkers seen through known cameras, for the calibration-from-walkers tests: head and foot
// points projected through the camera (a round head's silhouette top, the foot point 15% of
// the height up), walkers of drawn heights leaning forward, pixel noise. The same seed
// draws the same people for every camera, so several cameras can watch one crowd.
#pragma once

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include <Eigen/Geometry>

#include "calibration/camera.h"
#include "calibration/walker_calibration.h"

namespace jgpm::test {

inline constexpr double kDeg = std::numbers::pi / 180;

// A camera at `height_mm` above the origin looking along +z, `tilt_deg` down, rolled.
inline Camera Placed(int width, int height, double focal, double height_mm, double tilt_deg, double roll_deg) {
  const Eigen::Vector3d centre(0, height_mm, 0);
  const double t = tilt_deg * kDeg;
  Camera camera = LookAtCamera("truth", width, height, focal, centre,
                               centre + Eigen::Vector3d(0, -std::sin(t), std::cos(t)));
  camera.cam_from_world_rotation =
      Eigen::AngleAxisd(roll_deg * kDeg, Eigen::Vector3d::UnitZ()).toRotationMatrix() * camera.cam_from_world_rotation;
  camera.cam_from_world_translation_mm = -camera.cam_from_world_rotation * centre;
  return camera;
}

struct Walk {
  Eigen::Vector3d from, to;  // floor points, mm
};

// The top of a round head's image whose top point is `top`: the highest of points all
// over its upper half (radius 90 mm), found by brute force.
inline bool SilhouetteTop(const Camera& camera, const Eigen::Vector3d& top, Eigen::Vector2d* pixel) {
  const double r = 90;
  const Eigen::Vector3d centre = top - Eigen::Vector3d(0, r, 0);
  bool any = false;
  for (int i = 0; i <= 45; ++i) {  // the upper half, in 2-degree steps
    for (int j = 0; j < 180; ++j) {
      const double polar = i * std::numbers::pi / 90, azimuth = j * std::numbers::pi / 90;
      const Eigen::Vector3d p = centre + r * Eigen::Vector3d(std::sin(polar) * std::cos(azimuth), std::cos(polar),
                                                             std::sin(polar) * std::sin(azimuth));
      Eigen::Vector2d q;
      if (camera.Project(p, &q) && (!any || q.y() < pixel->y())) {
        *pixel = q;
        any = true;
      }
    }
  }
  return any;
}

// Every walker on its walk, `frames` points each, heights drawn around 1700 +- 90 mm, the
// head leaning forward along the walk by 2-6 degrees, the points given noise of `noise_px`;
// points outside the image are dropped, as a blob touching the edge would be. Walker w
// starts at frame w * stagger (0: frames, one after another), numbered w * 7 + 3.
// `foot_share_spread`: each walker's foot point is at its own share of their height,
// drawn uniformly within 0.15 +- it (a coat or a skirt moves the legs' lowest 30%), which
// the calibration, taking 0.15 for everyone, does not know.
inline std::vector<HeadFoot> Observe(const Camera& camera, const std::vector<Walk>& walks, int frames,
                                     double noise_px, unsigned seed, double* mean_height = nullptr,
                                     int stagger = 0, double foot_share_spread = 0) {
  std::mt19937 people(seed), pixels(seed + 1000);
  std::normal_distribution<double> stature(1700, 90), noise(0, noise_px);
  std::uniform_real_distribution<double> lean_deg(2, 6);
  std::vector<HeadFoot> points;
  double sum = 0;
  for (size_t w = 0; w < walks.size(); ++w) {
    const double height = stature(people);
    sum += height;
    const Eigen::Vector3d lean =
        (walks[w].to - walks[w].from).normalized() * height * std::tan(lean_deg(people) * kDeg);
    const double foot_share =
        0.15 + (foot_share_spread > 0 ? std::uniform_real_distribution<double>(-1, 1)(people) * foot_share_spread : 0);
    for (int i = 0; i < frames; ++i) {
      const Eigen::Vector3d foot = walks[w].from + (walks[w].to - walks[w].from) * i / (frames - 1.0);
      HeadFoot point;
      point.walker = static_cast<int>(w) * 7 + 3;  // any numbering
      point.frame = static_cast<int>(w) * (stagger > 0 ? stagger : frames) + i;
      // The foot point: the centroid of the legs' lowest 30%, 15% of the height up
      // (WalkerCalibrationOptions::foot_share).
      if (!camera.Project(foot + Eigen::Vector3d(0, foot_share * height, 0), &point.foot_px) ||
          !SilhouetteTop(camera, foot + lean + Eigen::Vector3d(0, height, 0), &point.head_px))
        continue;
      auto inside = [&](const Eigen::Vector2d& p) {
        return p.x() > 0 && p.y() > 0 && p.x() < camera.width - 1 && p.y() < camera.height - 1;
      };
      if (!inside(point.foot_px) || !inside(point.head_px)) continue;
      point.head_px += Eigen::Vector2d(noise(pixels), noise(pixels));
      point.foot_px += Eigen::Vector2d(noise(pixels), noise(pixels));
      points.push_back(point);
    }
  }
  if (mean_height) *mean_height = sum / walks.size();
  return points;
}

// Walks across and along the view at 6-20 m from a camera over a plaza: 6, and 6 more.
inline std::vector<Walk> PlazaWalks() {
  return {{{-6000, 0, 8000}, {6000, 0, 9000}},   {{5000, 0, 12000}, {-5000, 0, 11000}},
          {{-4000, 0, 16000}, {4000, 0, 18000}}, {{-2000, 0, 7000}, {1000, 0, 19000}},
          {{3000, 0, 20000}, {2000, 0, 8000}},   {{-7000, 0, 14000}, {7000, 0, 14500}},
          {{6000, 0, 7000}, {-6000, 0, 7500}},   {{-5000, 0, 10000}, {5000, 0, 10500}},
          {{4000, 0, 18000}, {-4000, 0, 15000}}, {{2500, 0, 6500}, {-1500, 0, 17000}},
          {{-3000, 0, 19000}, {-2000, 0, 9000}}, {{7000, 0, 13000}, {-7000, 0, 12000}}};
}

}  // namespace jgpm::test
