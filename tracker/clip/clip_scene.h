// What stands between the cameras and a synthetic walker, and the light that casts the
// walker's shadow: the parts of a real scene that a silhouette tracker meets and the
// tracker's own clips never had.
//
// Occluders: static objects on the floor, each placed on the line from one camera (taken
// in turn) to a point of the walk, 55-85% of the way (nearer the camera, a table hides
// only the floor), and clear of every place the walker's root passes by its footprint and
// 0.4 m, so they hide part of the walker in some frames of that camera
// without being walked through: a pillar (0.3-0.5 m across, 2.6 m high), a table (1.2 x
// 0.7 m at 0.73 m) or a parked bicycle. They are part of the background (the empty-room
// plate shows them) and hide the walker wherever they are nearer than him, in the video
// and in the masks (a mask is what can be seen of the walker).
//
// Shadow: a distant light 35-65 degrees above the floor from a random side; the floor
// points whose ray to the light meets the walker are darkened to 40-60% (a real indoor
// shadow), in the video only, as the exact masks are the walker alone. The observed masks
// keep it, as a segmentation without shadow removal does.
//
// Glossy floor: the floor reflects the walkers with reflectance `reflection` (a polished
// hall or a wet street 0.1-0.3): each floor pixel is blended with the walkers mirrored in
// the floor plane, in the video only. The observed masks keep the reflection where it
// changes the floor by more than kReflectionSeenLevels grey levels, as a background
// subtraction would see it.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core/mat.hpp>

#include "calibration/camera.h"
#include "tracker/body/body_model.h"
#include "tracker/body/ray_caster.h"

namespace jgpm {

struct SceneOptions {
  int occluders = 0;    // static objects (pillar, table, bicycle), 0-8
  bool shadow = false;  // the walker's cast shadow
  double reflection = 0;  // the floor's reflectance, 0 (matt) to 0.5

  bool Check(std::string* why) const;
};

// An oriented box: centre, unit axes as columns, half extents along them.
struct SceneBox {
  Eigen::Vector3d centre_mm = Eigen::Vector3d::Zero();
  Eigen::Matrix3d axes = Eigen::Matrix3d::Identity();
  Eigen::Vector3d half_mm = Eigen::Vector3d::Zero();
};

// Where the unit ray origin + t direction first meets the box (t >= 0), with the outward
// normal there; false when it misses.
bool IntersectBox(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction, const SceneBox& box, double* t,
                  Eigen::Vector3d* normal);

struct SceneObject {
  std::string kind;  // "pillar", "table", "bicycle"
  std::vector<Capsule> capsules;
  std::vector<SceneBox> boxes;
  cv::Vec3f colour_bgr;
};

// A reflection that changes a floor pixel by more than this (grey levels, any channel) is in
// the observed masks: MOG2's default threshold is 4 standard deviations, and the clips'
// sensor noise 2-6 levels.
constexpr double kReflectionSeenLevels = 20;

// The capsules mirrored in the floor plane y = 0 (their reflection in a glossy floor).
std::vector<Capsule> MirroredInFloor(std::vector<Capsule> capsules);

class ClipScene {
 public:
  // `joints`: the walk's bone ends per frame (its root path keeps objects off it). Objects,
  // light and shadow strength are drawn from `seed` alone.
  ClipScene(const SceneOptions& options, const std::vector<Camera>& cameras,
            const std::vector<Eigen::Matrix3Xd>& joints, uint64_t seed);

  const SceneOptions& options() const { return options_; }
  const std::vector<SceneObject>& objects() const { return objects_; }
  // Unit direction towards the light, and the floor's brightness in the shadow.
  const Eigen::Vector3d& light() const { return light_; }
  double shadow_gain() const { return shadow_gain_; }

  // Per pixel of the caster's camera: distance along the ray to the nearest object
  // (CV_32F, +inf where none) and its shaded colour (CV_32FC3, BGR).
  void RenderObjects(const RayCaster& caster, cv::Mat* depth_mm, cv::Mat* colour) const;
  // 255 where the pixel sees the floor (nearer than `objects_depth` and, within the room,
  // nearer than its walls: centre and radius as RenderBackground has them), 0 elsewhere.
  // The same for every frame of a camera (the objects do not move).
  static void VisibleFloor(const RayCaster& caster, const cv::Mat& objects_depth, const Eigen::Vector3d& room_centre_mm,
                           double room_radius_mm, cv::Mat* floor);
  // 255 where the pixel sees the floor (`floor`, from VisibleFloor) in the shadow of
  // `body`; 0 elsewhere, and everywhere without a shadow.
  void RenderShadow(const RayCaster& caster, const std::vector<Capsule>& body, const cv::Mat& floor,
                    cv::Mat* shadow) const;

 private:
  SceneOptions options_;
  std::vector<SceneObject> objects_;
  Eigen::Vector3d light_ = Eigen::Vector3d::UnitY();
  double shadow_gain_ = 1;
};

}  // namespace jgpm
