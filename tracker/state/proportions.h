// A person's limb lengths for their height: legs and arms longer or shorter than the
// model's skeleton has them, beyond the one size that scales every bone. The CMU
// subjects' leg / torso length ratio spans 1.21-1.36 and their arm / torso ratio
// 0.69-0.81 (femur + tibia, humerus + radius, against the spine, neck and head in each
// subject's ASF): up to 7% either way of a model's. With size alone, a walker of shorter
// legs is drawn with the hips too high or the whole body too small (the suite's 39_12
// walker: 35.7 mm with the model's skeleton, 19.1 with the subject's own).
#pragma once

#include <vector>

#include <Eigen/Core>

#include "io/mocap/skeleton.h"

namespace jgpm {

struct Proportions {
  double legs = 1;  // every leg bone's length (femur to toes) times this
  double arms = 1;  // every arm bone's length (humerus to fingers) times this
  bool operator==(const Proportions&) const = default;
};

// Applies proportions to root-relative bone ends (Kinematics' columns, root at 0).
class LimbScaler {
 public:
  // InputError naming the skeleton when it lacks one of the CMU limb bones.
  explicit LimbScaler(const Skeleton& skeleton);
  // Each leg's bone ends move away from (or toward) its hip joint's end, each arm's from
  // its clavicle's end, by the proportion; the lowest foot joint's height (what the body
  // stands on) is taken again. Nothing changes at proportions 1.
  void Apply(const Proportions& proportions, Eigen::Matrix3Xd* relative, double* foot_height_mm) const;

 private:
  struct Chain {
    int base = 0;
    std::vector<int> joints;
    bool leg = true;
  };
  std::vector<Chain> chains_;
  std::vector<int> feet_;
};

}  // namespace jgpm
