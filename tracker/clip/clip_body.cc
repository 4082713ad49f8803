#include "tracker/clip/clip_body.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

#include "io/base/enum_name.h"
#include "io/base/error.h"

namespace jgpm {
namespace {

ClipMaterial Material(BodyMaterial material) {
  switch (material) {
    case BodyMaterial::kSkin: return ClipMaterial::kSkin;
    case BodyMaterial::kShirt: return ClipMaterial::kShirt;
    case BodyMaterial::kTrousers: return ClipMaterial::kTrousers;
    case BodyMaterial::kShoes: return ClipMaterial::kShoes;
  }
  return ClipMaterial::kShirt;
}

// A person's widths relative to the adult mean the tracker's body has. Spreads: adult
// girths vary by about 10-15% (1 standard deviation) around their mean, so overall 0.12,
// truncated at 2 standard deviations (the issue's +-25%); the regions vary a little apart
// from it; heads vary less than bodies, hands and shoulders about as much.
struct Proportions {
  double torso = 1, belly = 1, shoulders = 1, arms = 1, hands = 1, legs = 1, feet = 1, head = 1;
};

Proportions DrawProportions(uint64_t seed) {
  Proportions p;
  if (seed == 0) return p;
  std::mt19937_64 rng(seed * 0x9E3779B97F4A7C15ull + 0x2545F4914F6CDD1Dull);
  std::normal_distribution<double> normal(0, 1);
  auto z = [&] { return std::clamp(normal(rng), -2.0, 2.0); };
  const double overall = 1 + 0.12 * z();
  p.torso = overall * (1 + 0.05 * z());
  p.belly = p.torso * (1 + 0.06 * z());
  p.shoulders = 1 + 0.08 * z();
  p.arms = overall * (1 + 0.06 * z());
  p.hands = 1 + 0.08 * z();
  p.legs = overall * (1 + 0.06 * z());
  p.feet = 1 + 0.05 * z();
  p.head = 1 + 0.05 * z();
  return p;
}

double Factor(const std::string& part, const Proportions& p) {
  auto is = [&](std::initializer_list<const char*> names) {
    return std::any_of(names.begin(), names.end(), [&](const char* n) { return part == n; });
  };
  if (is({"pelvis", "chest", "lowerneck", "upperneck"})) return p.torso;
  if (is({"lowerback", "upperback"})) return p.belly;
  if (is({"shoulders", "lclavicle", "rclavicle"})) return p.shoulders;
  if (is({"lhumerus", "rhumerus", "lradius", "rradius", "lwrist", "rwrist"})) return p.arms;
  if (is({"lhand", "rhand", "lfingers", "rfingers", "lthumb", "rthumb"})) return p.hands;
  if (is({"lfemur", "rfemur", "ltibia", "rtibia"})) return p.legs;
  if (is({"lfoot", "rfoot", "ltoes", "rtoes"})) return p.feet;
  if (is({"head"})) return p.head;
  return 1;
}

}  // namespace

std::string_view ClothingName(Clothing clothing) {
  switch (clothing) {
    case Clothing::kNone: return "none";
    case Clothing::kTrousers: return "trousers";
    case Clothing::kCoat: return "coat";
    case Clothing::kSkirt: return "skirt";
  }
  return "?";
}

bool ParseClothing(std::string_view name, Clothing* clothing) {
  return ParseByName(name, {Clothing::kNone, Clothing::kTrousers, Clothing::kCoat, Clothing::kSkirt}, ClothingName,
                     clothing);
}

bool ClipBodyOptions::Check(std::string* why) const {
  BodyModelOptions widths;
  widths.width_scale = width_scale;
  return widths.Check(why);
}

ClipBody::ClipBody(const Skeleton& skeleton, const ClipBodyOptions& options, const std::string& source) {
  std::string why;
  if (!options.Check(&why)) ThrowInputError(source, "body: " + why);
  for (const Bone& bone : skeleton.bones) bone_names_.push_back(bone.name);
  const BodyModel body(skeleton, {}, source);  // the tracker's body, width 1
  const Proportions proportions = DrawProportions(options.body_seed);
  const bool loose_legs = options.clothing == Clothing::kTrousers;
  const bool thick_sleeves = options.clothing == Clothing::kCoat;
  for (const BodyPart& part : body.parts()) {
    ClipShape s;
    s.name = part.name;
    s.from = {{part.from_joint, 1.0}};
    s.to = {{part.to_joint, 1.0}};
    double factor = Factor(part.name, proportions);
    // Loose trousers stand off the legs (~2-3 cm), a coat's sleeves off the arms.
    if (loose_legs && (part.name == "lfemur" || part.name == "rfemur")) factor *= 1.25;
    if (loose_legs && (part.name == "ltibia" || part.name == "rtibia")) factor *= 1.4;
    if (thick_sleeves && (part.name == "lhumerus" || part.name == "rhumerus" || part.name == "lradius" ||
                          part.name == "rradius")) {
      factor *= 1.35;
    }
    s.radius_from_mm = part.radius_from_mm * factor * options.width_scale;
    s.radius_to_mm = part.radius_to_mm * factor * options.width_scale;
    s.material = Material(part.material);
    if (thick_sleeves && (part.name == "lhumerus" || part.name == "rhumerus" || part.name == "lradius" ||
                          part.name == "rradius")) {
      s.material = ClipMaterial::kCoat;
    }
    shapes_.push_back(s);
  }
  auto joint = [&](const char* bone) {
    const int index = skeleton.FindBone(bone);
    if (index < 0) ThrowInputError(source, std::string("the clip's body needs the CMU bone '") + bone + "'");
    return index;
  };
  const int lhip = joint("lhipjoint"), rhip = joint("rhipjoint"), lknee = joint("lfemur"), rknee = joint("rfemur");
  // A point `along` the way from the hips' centre to the knees' centre.
  auto thigh = [&](double along) {
    return std::vector<std::pair<int, double>>{
        {lhip, 0.5 * (1 - along)}, {rhip, 0.5 * (1 - along)}, {lknee, 0.5 * along}, {rknee, 0.5 * along}};
  };
  const double w = options.width_scale * proportions.legs;
  auto add = [&](const char* name, std::vector<std::pair<int, double>> from, std::vector<std::pair<int, double>> to,
                 double r_from, double r_to, ClipMaterial material) {
    ClipShape s;
    s.name = name;
    s.from = std::move(from);
    s.to = std::move(to);
    s.radius_from_mm = r_from;
    s.radius_to_mm = r_to;
    s.material = material;
    shapes_.push_back(s);
    return &shapes_.back();
  };
  switch (options.clothing) {
    case Clothing::kNone:
      break;
    case Clothing::kTrousers:
      // The cloth between the legs, from the crotch a third of the way to the knees.
      add("crotch", thigh(0.05), thigh(0.4), 100 * w, 80 * w, ClipMaterial::kTrousers);
      break;
    case Clothing::kCoat: {
      const double t = options.width_scale * proportions.belly;
      add("coat", {{joint("upperback"), 1.0}}, thigh(0.55), 150 * t, 195 * t, ClipMaterial::kCoat);
      break;
    }
    case Clothing::kSkirt:
      add("skirt", thigh(0.0), thigh(0.85), 150 * w, 245 * w, ClipMaterial::kSkirt);
      break;
  }
  if (options.bag) {
    // A bag of about 30 x 25 x 18 cm beside the right hip, hanging from a strap over the
    // left shoulder: it moves with the pelvis, not with the legs.
    const std::vector<std::pair<int, double>> side = {{rhip, 2.0}, {lhip, -1.0}};
    ClipShape* bag = add("bag", side, side, 95 * options.width_scale, 95 * options.width_scale, ClipMaterial::kBag);
    bag->from_offset_mm = Eigen::Vector3d(0, 60, 0);
    bag->to_offset_mm = Eigen::Vector3d(0, -100, 0);
    ClipShape* strap = add("strap", {{joint("lclavicle"), 1.0}}, side, 14, 14, ClipMaterial::kBag);
    strap->to_offset_mm = Eigen::Vector3d(0, 60, 0);
  }
}

void ClipBody::Place(const Eigen::Matrix3Xd& joints, std::vector<Capsule>* capsules) const {
  JGPM_CHECK(joints.cols() == static_cast<int>(bone_names_.size()));
  capsules->resize(shapes_.size());
  auto end = [&](const std::vector<std::pair<int, double>>& weights, const Eigen::Vector3d& offset) {
    if (weights.size() == 1 && weights[0].second == 1.0 && offset.isZero()) return Eigen::Vector3d(joints.col(weights[0].first));
    Eigen::Vector3d p = offset;
    for (const auto& [column, weight] : weights) p += weight * joints.col(column);
    return p;
  };
  for (size_t i = 0; i < shapes_.size(); ++i) {
    const ClipShape& s = shapes_[i];
    Capsule& c = (*capsules)[i];
    c.from_mm = end(s.from, s.from_offset_mm);
    c.to_mm = end(s.to, s.to_offset_mm);
    c.radius_from_mm = s.radius_from_mm;
    c.radius_to_mm = s.radius_to_mm;
  }
}

std::string ClipBody::EndText(const std::vector<std::pair<int, double>>& end, const Eigen::Vector3d& offset) const {
  std::string text;
  for (const auto& [column, weight] : end) {
    char term[96];
    if (weight == 1.0) std::snprintf(term, sizeof term, "%s", bone_names_[column].c_str());
    else std::snprintf(term, sizeof term, "%g %s", weight, bone_names_[column].c_str());
    text += (text.empty() ? "" : " + ") + std::string(term);
  }
  if (!offset.isZero()) {
    char term[96];
    std::snprintf(term, sizeof term, " + (%g, %g, %g) mm", offset.x(), offset.y(), offset.z());
    text += term;
  }
  return text;
}

}  // namespace jgpm
