#include "tracker/body/body_model.h"

#include <cmath>

#include "io/base/error.h"

namespace jgpm {
namespace {

// A part between the ends of two bones ("root": the root position), with its radii at
// each end (millimetres, average adult). Limbs run from their parent's end to their own.
struct PartSpec {
  const char* name;
  const char* from;
  const char* to;
  double radius_from_mm;
  double radius_to_mm;
  BodyMaterial material;
};

constexpr BodyMaterial kSkin = BodyMaterial::kSkin, kShirt = BodyMaterial::kShirt,
                       kTrousers = BodyMaterial::kTrousers, kShoes = BodyMaterial::kShoes;

// Radii chosen so the front and side silhouettes of the CMU subjects' rest poses have
// roughly human widths: hips ~350 mm, chest ~330 x 230 mm, thigh ~160 mm at the top.
const PartSpec kParts[] = {
    {"pelvis", "lhipjoint", "rhipjoint", 85, 85, kTrousers},
    {"lowerback", "root", "lowerback", 105, 110, kShirt},
    {"upperback", "lowerback", "upperback", 110, 115, kShirt},
    {"chest", "upperback", "thorax", 115, 100, kShirt},
    {"shoulders", "lclavicle", "rclavicle", 55, 55, kShirt},
    {"lclavicle", "thorax", "lclavicle", 70, 58, kShirt},
    {"rclavicle", "thorax", "rclavicle", 70, 58, kShirt},
    {"lowerneck", "thorax", "lowerneck", 50, 48, kSkin},
    {"upperneck", "lowerneck", "upperneck", 48, 48, kSkin},
    {"head", "upperneck", "head", 78, 88, kSkin},
    {"lhumerus", "lclavicle", "lhumerus", 52, 42, kShirt},
    {"rhumerus", "rclavicle", "rhumerus", 52, 42, kShirt},
    {"lradius", "lhumerus", "lradius", 40, 33, kSkin},
    {"rradius", "rhumerus", "rradius", 40, 33, kSkin},
    {"lwrist", "lradius", "lwrist", 33, 28, kSkin},
    {"rwrist", "rradius", "rwrist", 33, 28, kSkin},
    {"lhand", "lwrist", "lhand", 36, 32, kSkin},
    {"rhand", "rwrist", "rhand", 36, 32, kSkin},
    {"lfingers", "lhand", "lfingers", 28, 22, kSkin},
    {"rfingers", "rhand", "rfingers", 28, 22, kSkin},
    {"lthumb", "lwrist", "lthumb", 18, 15, kSkin},
    {"rthumb", "rwrist", "rthumb", 18, 15, kSkin},
    {"lfemur", "lhipjoint", "lfemur", 80, 55, kTrousers},
    {"rfemur", "rhipjoint", "rfemur", 80, 55, kTrousers},
    {"ltibia", "lfemur", "ltibia", 52, 40, kTrousers},
    {"rtibia", "rfemur", "rtibia", 52, 40, kTrousers},
    {"lfoot", "ltibia", "lfoot", 42, 34, kShoes},
    {"rfoot", "rtibia", "rfoot", 42, 34, kShoes},
    {"ltoes", "lfoot", "ltoes", 32, 26, kShoes},
    {"rtoes", "rfoot", "rtoes", 32, 26, kShoes},
};

}  // namespace

bool BodyModelOptions::Check(std::string* why) const {
  if (!(std::isfinite(width_scale) && width_scale > 0.2 && width_scale < 5)) {
    if (why) *why = "width scale must be in (0.2, 5)";
    return false;
  }
  return true;
}

BodyModel::BodyModel(const Skeleton& skeleton, const BodyModelOptions& options,
                     const std::string& source)
    : num_joints_(static_cast<int>(skeleton.bones.size())) {
  std::string why;
  if (!options.Check(&why)) ThrowInputError(source, "body model: " + why);
  auto joint = [&](const char* bone) {
    const int index = skeleton.FindBone(bone);
    if (index < 0)
      ThrowInputError(source, std::string("the body model needs the CMU bone '") + bone +
                                  "', which the skeleton lacks");
    return index;  // Kinematics column b is the end of bone b; the root's is its position
  };
  for (const PartSpec& spec : kParts) {
    BodyPart part;
    part.name = spec.name;
    part.from_joint = joint(spec.from);
    part.to_joint = joint(spec.to);
    part.radius_from_mm = spec.radius_from_mm * options.width_scale;
    part.radius_to_mm = spec.radius_to_mm * options.width_scale;
    part.material = spec.material;
    parts_.push_back(part);
  }
}

void BodyModel::Place(const Eigen::Matrix3Xd& joint_in_world_mm,
                      std::vector<Capsule>* capsules) const {
  JGPM_CHECK(joint_in_world_mm.cols() == num_joints_);
  capsules->resize(parts_.size());
  for (size_t i = 0; i < parts_.size(); ++i) {
    const BodyPart& part = parts_[i];
    Capsule& c = (*capsules)[i];
    c.from_mm = joint_in_world_mm.col(part.from_joint);
    c.to_mm = joint_in_world_mm.col(part.to_joint);
    c.radius_from_mm = part.radius_from_mm;
    c.radius_to_mm = part.radius_to_mm;
  }
}

std::vector<Capsule> BodyModel::Place(const Eigen::Matrix3Xd& joint_in_world_mm) const {
  std::vector<Capsule> capsules;
  Place(joint_in_world_mm, &capsules);
  return capsules;
}

}  // namespace jgpm
