// The volumetric body the tracker draws: one tapered capsule per limb segment (the convex
// hull of two spheres, radii interpolated linearly between its ends), a torso of spine,
// pelvis and shoulder capsules, and a head. Segment ends are joints of the ASF skeleton,
// so lengths follow the subject's bones; widths are adult defaults times a scale, and
// times a scale per region of the body (a build: broad shoulders and thin legs; clothes:
// a coat's wider torso and thighs), which the tracker learns (tracker/filter/body_shape.h).
//
// And a garment the limbs cannot draw: a skirt or a coat's tails hang as one cone from the
// hips round both thighs, filling the space between them that no pose of the legs fills
// without spreading them. The cone runs from the hips' centre kGarmentLength of the way
// to the knees' centre (0.75: between a coat's mid-thigh and a skirt above the knee), of
// radius garment x (150 mm at the top, 200 mm at the hem: at garment 1 a hem about 0.4 m
// across, a knee-length A-line skirt's). Garment 0, the default, draws none; the tracker
// learns it with the build, from 0, so it grows only where the silhouettes ask for it.
#pragma once

#include <array>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "io/mocap/skeleton.h"

namespace jgpm {

// What a part is dressed in: the synthetic clips colour parts by it.
enum class BodyMaterial { kSkin, kShirt, kTrousers, kShoes };

// Regions of the body whose widths scale together.
enum class BodyRegion { kTorso, kHead, kArms, kThighs, kShins };
constexpr int kNumBodyRegions = 5;
using RegionScales = std::array<double, kNumBodyRegions>;
constexpr RegionScales kUnitRegionScales = {1, 1, 1, 1, 1};
std::string_view BodyRegionName(BodyRegion region);  // "torso", "head", "arms", "thighs", "shins"

struct BodyPart {
  std::string name;
  BodyRegion region = BodyRegion::kTorso;
  // Kinematics columns (bone ends; column 0 the root position) of its two ends.
  int from_joint = 0;
  int to_joint = 0;
  double radius_from_mm = 0;
  double radius_to_mm = 0;
  BodyMaterial material = BodyMaterial::kShirt;
  // The radii at width scale 1 and region scale 1.
  double base_from_mm = 0;
  double base_to_mm = 0;
};

// A part placed in the world.
struct Capsule {
  Eigen::Vector3d from_mm;
  Eigen::Vector3d to_mm;
  double radius_from_mm = 0;
  double radius_to_mm = 0;
};

// How finely the body is cut into parts. kFull: all 30 parts (body_model.cc; what clips are
// rendered with). kTracking: what the tracker draws for every particle and camera, where a
// part costs about the same whatever its size. The rule: a chain of parts 1-4 px across at
// the tracker's working resolution (a walker 80-200 px tall, 9-21 mm a pixel) that is
// nearly straight is drawn as one part: each hand (the forearm's wrist end, the hand, the
// fingers) and the neck. The thumbs are as small but stick out from the hands to the
// front, one of the few cues to which way a walker faces: without them a walker facing away
// from the particles was come round to in 3-23 frames or not at all (tracker_test, seeds
// 1-8: 6 7 23 6 3 4 9 never), with them in 1-10 (4 10 7 8 1 2 9 10; the full body 5 3 10 6 1
// 4 5 9). 25 parts instead of 30.
enum class BodyDetail { kFull, kTracking };

struct BodyModelOptions {
  // Multiplies every default radius (1: an average adult; ~0.85 slim, ~1.2 broad).
  double width_scale = 1.0;
  BodyDetail detail = BodyDetail::kFull;

  bool Check(std::string* why) const;
};

class BodyModel {
 public:
  // InputError naming `source` when the skeleton lacks one of the CMU bones a part needs
  // or the options are invalid.
  BodyModel(const Skeleton& skeleton, const BodyModelOptions& options, const std::string& source);

  const std::vector<BodyPart>& parts() const { return parts_; }
  // Every part's radii: its base radii times the width scale times its region's scale.
  // Not thread-safe with Place: set between frames.
  void SetRegionScales(const RegionScales& scales);
  const RegionScales& region_scales() const { return region_scales_; }
  // The garment's scale (0: none, the default; finite and >= 0). Not thread-safe with Place.
  void SetGarment(double garment);
  double garment() const { return garment_; }
  int NumParts() const { return static_cast<int>(parts_.size()); }
  // The parts placed at joint positions (Kinematics::Compute's output, millimetres), then
  // the garment's cone when there is one (capsules beyond NumParts() are garments).
  void Place(const Eigen::Matrix3Xd& joint_in_world_mm, std::vector<Capsule>* capsules) const;
  std::vector<Capsule> Place(const Eigen::Matrix3Xd& joint_in_world_mm) const;
  // The same with every radius times `scale`, the regions scaled by `shape` and the
  // garment `garment` instead of region_scales() and garment().
  void Place(const Eigen::Matrix3Xd& joint_in_world_mm, double scale, const RegionScales& shape, double garment,
             std::vector<Capsule>* capsules) const;

 private:
  std::vector<BodyPart> parts_;
  int num_joints_ = 0;
  double width_scale_ = 1;
  RegionScales region_scales_ = kUnitRegionScales;
  double garment_ = 0;
  int lhip_ = 0, rhip_ = 0, lknee_ = 0, rknee_ = 0;  // the garment's columns
  void PlaceGarment(const Eigen::Matrix3Xd& joint_in_world_mm, double radius_scale,
                    std::vector<Capsule>* capsules) const;
};

constexpr double kGarmentLength = 0.75;                      // of the way from the hips to the knees
constexpr double kGarmentTopMm = 150, kGarmentHemMm = 200;  // radii at garment 1

}  // namespace jgpm
