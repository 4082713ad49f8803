#include "tracker/state/proportions.h"

#include <algorithm>
#include <string>

#include "io/base/error.h"

namespace jgpm {

LimbScaler::LimbScaler(const Skeleton& skeleton) {
  const auto bone = [&](const std::string& name) {
    const int b = skeleton.FindBone(name);
    if (b < 0) ThrowInputError("the model's skeleton", "has no '" + name + "' bone, which limb proportions need");
    return b;
  };
  for (const char* side : {"l", "r"}) {
    const std::string s = side;
    chains_.push_back({bone(s + "hipjoint"), {bone(s + "femur"), bone(s + "tibia"), bone(s + "foot"), bone(s + "toes")}, true});
    chains_.push_back({bone(s + "clavicle"),
                       {bone(s + "humerus"), bone(s + "radius"), bone(s + "wrist"), bone(s + "hand"), bone(s + "fingers"),
                        bone(s + "thumb")},
                       false});
  }
  feet_ = skeleton.FootBones();
}

void LimbScaler::Apply(const Proportions& proportions, Eigen::Matrix3Xd* relative, double* foot_height_mm) const {
  if (proportions == Proportions{}) return;
  for (const Chain& chain : chains_) {
    const double scale = chain.leg ? proportions.legs : proportions.arms;
    const Eigen::Vector3d base = relative->col(chain.base);
    for (int j : chain.joints) relative->col(j) = base + scale * (relative->col(j) - base);
  }
  double foot = 1e300;
  for (int b : feet_) foot = std::min(foot, (*relative)(1, b));
  *foot_height_mm = foot;
}

}  // namespace jgpm
