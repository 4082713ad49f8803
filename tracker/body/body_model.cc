#include "tracker/body/body_model.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <string_view>

#include "io/base/error.h"

namespace jgpm {
namespace {

// A part between the ends of two bones ("root": the root position), with its radii at
// each end (millimetres, average adult). Limbs run from their parent's end to their own.
struct PartSpec {
  const char* name;
  BodyRegion region;
  const char* from;
  const char* to;
  double radius_from_mm;
  double radius_to_mm;
  BodyMaterial material;
};

constexpr BodyRegion kTorso = BodyRegion::kTorso, kHead = BodyRegion::kHead, kArms = BodyRegion::kArms,
                     kThighs = BodyRegion::kThighs, kShins = BodyRegion::kShins;
constexpr BodyMaterial kSkin = BodyMaterial::kSkin, kShirt = BodyMaterial::kShirt,
                       kTrousers = BodyMaterial::kTrousers, kShoes = BodyMaterial::kShoes;

// Radii chosen so the front and side silhouettes of the CMU subjects' rest poses have
// roughly human widths: hips ~350 mm, chest ~330 x 230 mm, thigh ~160 mm at the top.
const PartSpec kParts[] = {
    {"pelvis", kTorso, "lhipjoint", "rhipjoint", 85, 85, kTrousers},
    {"lowerback", kTorso, "root", "lowerback", 105, 110, kShirt},
    {"upperback", kTorso, "lowerback", "upperback", 110, 115, kShirt},
    {"chest", kTorso, "upperback", "thorax", 115, 100, kShirt},
    {"shoulders", kTorso, "lclavicle", "rclavicle", 55, 55, kShirt},
    {"lclavicle", kTorso, "thorax", "lclavicle", 70, 58, kShirt},
    {"rclavicle", kTorso, "thorax", "rclavicle", 70, 58, kShirt},
    {"lowerneck", kHead, "thorax", "lowerneck", 50, 48, kSkin},
    {"upperneck", kHead, "lowerneck", "upperneck", 48, 48, kSkin},
    {"head", kHead, "upperneck", "head", 78, 88, kSkin},
    {"lhumerus", kArms, "lclavicle", "lhumerus", 52, 42, kShirt},
    {"rhumerus", kArms, "rclavicle", "rhumerus", 52, 42, kShirt},
    {"lradius", kArms, "lhumerus", "lradius", 40, 33, kSkin},
    {"rradius", kArms, "rhumerus", "rradius", 40, 33, kSkin},
    {"lwrist", kArms, "lradius", "lwrist", 33, 28, kSkin},
    {"rwrist", kArms, "rradius", "rwrist", 33, 28, kSkin},
    {"lhand", kArms, "lwrist", "lhand", 36, 32, kSkin},
    {"rhand", kArms, "rwrist", "rhand", 36, 32, kSkin},
    {"lfingers", kArms, "lhand", "lfingers", 28, 22, kSkin},
    {"rfingers", kArms, "rhand", "rfingers", 28, 22, kSkin},
    {"lthumb", kArms, "lwrist", "lthumb", 18, 15, kSkin},
    {"rthumb", kArms, "rwrist", "rthumb", 18, 15, kSkin},
    {"lfemur", kThighs, "lhipjoint", "lfemur", 80, 55, kTrousers},
    {"rfemur", kThighs, "rhipjoint", "rfemur", 80, 55, kTrousers},
    {"ltibia", kShins, "lfemur", "ltibia", 52, 40, kTrousers},
    {"rtibia", kShins, "rfemur", "rtibia", 52, 40, kTrousers},
    {"lfoot", kShins, "ltibia", "lfoot", 42, 34, kShoes},
    {"rfoot", kShins, "rtibia", "rfoot", 42, 34, kShoes},
    {"ltoes", kShins, "lfoot", "ltoes", 32, 26, kShoes},
    {"rtoes", kShins, "rfoot", "rtoes", 32, 26, kShoes},
};

// BodyDetail::kTracking (body_model.h): a chain drawn as its first part, reaching to
// `to` with radius `radius_to_mm` there (the chain's last radius), and the parts left out.
struct Merge {
  std::string_view part;
  const char* to;
  double radius_to_mm;
};
const Merge kTrackingMerges[] = {
    {"lowerneck", "upperneck", 48}, {"lwrist", "lfingers", 22}, {"rwrist", "rfingers", 22}};
const std::string_view kTrackingLeftOut[] = {"upperneck", "lhand", "rhand", "lfingers", "rfingers"};

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
  const bool tracking = options.detail == BodyDetail::kTracking;
  for (PartSpec spec : kParts) {
    if (tracking) {
      if (std::ranges::find(kTrackingLeftOut, spec.name) != std::end(kTrackingLeftOut)) continue;
      for (const Merge& merge : kTrackingMerges) {
        if (spec.name == merge.part) spec.to = merge.to, spec.radius_to_mm = merge.radius_to_mm;
      }
    }
    BodyPart part;
    part.name = spec.name;
    part.region = spec.region;
    part.from_joint = joint(spec.from);
    part.to_joint = joint(spec.to);
    part.base_from_mm = spec.radius_from_mm;
    part.base_to_mm = spec.radius_to_mm;
    part.material = spec.material;
    parts_.push_back(part);
  }
  lhip_ = joint("lhipjoint");
  rhip_ = joint("rhipjoint");
  lknee_ = joint("lfemur");
  rknee_ = joint("rfemur");
  width_scale_ = options.width_scale;
  SetRegionScales(kUnitRegionScales);
}

std::string_view BodyRegionName(BodyRegion region) {
  static constexpr std::string_view kNames[] = {"torso", "head", "arms", "thighs", "shins"};
  return kNames[static_cast<int>(region)];
}

void BodyModel::SetRegionScales(const RegionScales& scales) {
  for (double s : scales) JGPM_CHECK(std::isfinite(s) && s > 0);
  region_scales_ = scales;
  for (BodyPart& part : parts_) {
    const double scale = width_scale_ * scales[static_cast<int>(part.region)];
    part.radius_from_mm = part.base_from_mm * scale;
    part.radius_to_mm = part.base_to_mm * scale;
  }
}

void BodyModel::SetGarment(double garment) {
  JGPM_CHECK(std::isfinite(garment) && garment >= 0);
  garment_ = garment;
}

void BodyModel::PlaceGarment(const Eigen::Matrix3Xd& joint_in_world_mm, double radius_scale,
                             std::vector<Capsule>* capsules) const {
  if (!(radius_scale > 0)) return;
  const Eigen::Vector3d hips = 0.5 * (joint_in_world_mm.col(lhip_) + joint_in_world_mm.col(rhip_));
  const Eigen::Vector3d knees = 0.5 * (joint_in_world_mm.col(lknee_) + joint_in_world_mm.col(rknee_));
  Capsule c;
  c.from_mm = hips;
  c.to_mm = hips + kGarmentLength * (knees - hips);
  c.radius_from_mm = kGarmentTopMm * radius_scale;
  c.radius_to_mm = kGarmentHemMm * radius_scale;
  capsules->push_back(c);
}

void BodyModel::Place(const Eigen::Matrix3Xd& joint_in_world_mm,
                      std::vector<Capsule>* capsules) const {
  Place(joint_in_world_mm, 1.0, region_scales_, garment_, capsules);
}

void BodyModel::Place(const Eigen::Matrix3Xd& joint_in_world_mm, double scale, const RegionScales& shape,
                      double garment, std::vector<Capsule>* capsules) const {
  JGPM_CHECK(joint_in_world_mm.cols() == num_joints_);
  capsules->resize(parts_.size());
  for (size_t i = 0; i < parts_.size(); ++i) {
    const BodyPart& part = parts_[i];
    const double s = width_scale_ * scale * shape[static_cast<int>(part.region)];
    Capsule& c = (*capsules)[i];
    c.from_mm = joint_in_world_mm.col(part.from_joint);
    c.to_mm = joint_in_world_mm.col(part.to_joint);
    c.radius_from_mm = part.base_from_mm * s;
    c.radius_to_mm = part.base_to_mm * s;
  }
  PlaceGarment(joint_in_world_mm, width_scale_ * scale * garment, capsules);
}

std::vector<Capsule> BodyModel::Place(const Eigen::Matrix3Xd& joint_in_world_mm) const {
  std::vector<Capsule> capsules;
  Place(joint_in_world_mm, &capsules);
  return capsules;
}

}  // namespace jgpm
