// The volumetric body the tracker draws: one tapered capsule per limb segment (the convex
// hull of two spheres, radii interpolated linearly between its ends), a torso of spine,
// pelvis and shoulder capsules, and a head. Segment ends are joints of the ASF skeleton,
// so lengths follow the subject's bones; widths are adult defaults times a scale.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "io/mocap/skeleton.h"

namespace jgpm {

// What a part is dressed in: the synthetic clips colour parts by it.
enum class BodyMaterial { kSkin, kShirt, kTrousers, kShoes };

struct BodyPart {
  std::string name;
  // Kinematics columns (bone ends; column 0 the root position) of its two ends.
  int from_joint = 0;
  int to_joint = 0;
  double radius_from_mm = 0;
  double radius_to_mm = 0;
  BodyMaterial material = BodyMaterial::kShirt;
};

// A part placed in the world.
struct Capsule {
  Eigen::Vector3d from_mm;
  Eigen::Vector3d to_mm;
  double radius_from_mm = 0;
  double radius_to_mm = 0;
};

struct BodyModelOptions {
  // Multiplies every default radius (1: an average adult; ~0.85 slim, ~1.2 broad).
  double width_scale = 1.0;

  bool Check(std::string* why) const;
};

class BodyModel {
 public:
  // InputError naming `source` when the skeleton lacks one of the CMU bones a part needs
  // or the options are invalid.
  BodyModel(const Skeleton& skeleton, const BodyModelOptions& options, const std::string& source);

  const std::vector<BodyPart>& parts() const { return parts_; }
  int NumParts() const { return static_cast<int>(parts_.size()); }
  // The parts placed at joint positions (Kinematics::Compute's output, millimetres).
  void Place(const Eigen::Matrix3Xd& joint_in_world_mm, std::vector<Capsule>* capsules) const;
  std::vector<Capsule> Place(const Eigen::Matrix3Xd& joint_in_world_mm) const;

 private:
  std::vector<BodyPart> parts_;
  int num_joints_ = 0;
};

}  // namespace jgpm
