// Whether the masks hold the walker's shadow, and the light that casts it. A segmentation
// without shadow removal (or a shadow darker than MOG2's threshold, half the floor's
// brightness) keeps the shadow as foreground attached to the feet; a body that does not
// cast it explains that foreground with whatever it can move there: on the harsh clips,
// hidden legs reached into it and pulled a one-camera walker 0.6-0.7 m nearer (564 mm).
// With the light known the likelihood draws each particle's own shadow (likelihood.h),
// and the shadow is evidence for the right place instead of against it.
//
// The light is found by the likelihood itself: every `every` frames tracked well, the
// estimate is scored with its shadow cast from each light of a grid (azimuth every
// 15 degrees, elevation 20-80 degrees every 10) and with none; each light's gain (the
// cost without a shadow less the cost with it, summed over the cameras) is added up. Once
// `looks` looks have been made and the best light's mean gain is over `min_gain`, a finer
// grid about it (3 degrees, +-12 in azimuth and +-9 in elevation) is looked at as many
// times, and its best is taken for the rest of the run (a scene's light does not move in
// a clip's minutes; a restart keeps it). A light that explains nothing draws shadows
// where the masks have none, which costs: without a shadow the gains are mostly below 0.
// min_gain's rule: about twice the largest mean gain a clip without a shadow gave (the suites'
// clips, seed 1, after 6 looks: at most 0.021, the skirted monocular walk, falling to 0.005
// by its 10th look; a coat -0.06, bare walks -0.3 to -0.5), under what shadows in view
// gave (0.15-0.72 with two cameras or more). A webcam near the walk sees little of its
// walker's shadow within the region where the person is expected (0.01-0.07), and is
// mostly not found. The estimate must be roughly right for its shadow to tell: a walker
// already pulled into the shadow explains it with their own body (the harsh one-camera
// clip, 0.7 m off from the start: no light gains over 0.03).
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace jgpm {

struct ShadowLightOptions {
  bool enabled = true;
  int every = 5;          // frames between looks
  int looks = 6;          // looks on each grid before choosing from it
  double min_gain = 0.05;  // mean cost units a look by which the best light must beat none
  // After this many looks without a light, look only every `idle_every` frames (a scene
  // without shadows in its masks costs the looks' time for nothing).
  int idle_after = 30;
  int idle_every = 30;

  bool Check(std::string* why) const;
};

class ShadowLight {
 public:
  explicit ShadowLight(const ShadowLightOptions& options = {});

  // The light found (unit, towards it), or none yet.
  const std::optional<Eigen::Vector3d>& light() const { return light_; }
  // Its azimuth and elevation, degrees (Direction's).
  Eigen::Vector2d Angles() const;
  // Whether to look at this frame (counted from the first frame tracked well).
  bool Due();
  // One look: `cost(lights)` returns the estimate's cost under each light given, and for a
  // null entry with no shadow.
  using CostFunction = std::function<std::vector<double>(const std::vector<std::optional<Eigen::Vector3d>>&)>;
  void Look(const CostFunction& cost);

  // The unit direction towards a light `elevation_deg` above the floor, from
  // `azimuth_deg` (0 along +z, 90 along +x).
  static Eigen::Vector3d Direction(double azimuth_deg, double elevation_deg);

 private:
  void Coarse();  // azimuth every 15 degrees, elevation 20-80 every 10
  void Grid(double azimuth0, double azimuth_step, int azimuths, double elevation0, double elevation_step,
            int elevations);

  ShadowLightOptions options_;
  std::optional<Eigen::Vector3d> light_;
  std::vector<Eigen::Vector2d> candidates_;  // (azimuth, elevation), degrees
  std::vector<double> gains_;
  int looks_ = 0, total_looks_ = 0, frames_ = 0;
  bool fine_ = false;
};

}  // namespace jgpm
