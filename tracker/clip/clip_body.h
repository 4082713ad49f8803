// The person a synthetic clip shows, which need not be the body the tracker draws
// (tracker/body/body_model.h): with no options it is exactly that body (today's clips), so
// the tracker's likelihood is exact there; a body seed makes another person (widths drawn
// around the adult mean, thin to heavy; head and hands of other sizes; wider or narrower
// shoulders; bone lengths stay the subject's), and clothing and a bag add volumes the
// tracker's capsules cannot represent. Every shape is a round cone (the convex hull of two
// spheres, as the ray caster draws) between two points, each a weighted sum of bone ends
// plus an offset, so a skirt follows the thighs and a coat's hem swings with them.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "io/mocap/skeleton.h"
#include "tracker/body/body_model.h"

namespace jgpm {

enum class Clothing {
  kNone,      // the tracker's body: shirt and close trousers
  kTrousers,  // loose trousers: wider legs and a fill between the legs at the crotch
  kCoat,      // a coat from the chest to mid-thigh, swinging with the thighs, thick sleeves
  kSkirt,     // a cone from the hips to the knees that swings with the thighs
};
std::string_view ClothingName(Clothing clothing);  // "none", "trousers", "coat", "skirt"
bool ParseClothing(std::string_view name, Clothing* clothing);

struct ClipBodyOptions {
  double width_scale = 1.0;  // every width times this (after the seed's widths)
  uint64_t body_seed = 0;    // 0: the tracker's body; N > 0: another person for each N
  Clothing clothing = Clothing::kNone;
  bool bag = false;          // a shoulder bag at the right hip, its strap over the left shoulder

  bool Check(std::string* why) const;
  // Exactly the tracker's body (at width_scale): no seed, no clothing, no bag.
  bool TrackersBody() const { return body_seed == 0 && clothing == Clothing::kNone && !bag; }
};

enum class ClipMaterial { kSkin, kShirt, kTrousers, kShoes, kCoat, kSkirt, kBag };

// One rendered shape. An end is sum_k weight_k * bone_end(column_k) + offset (the world's
// y is up): a bone end, a point between bone ends, or one beside them.
struct ClipShape {
  std::string name;
  std::vector<std::pair<int, double>> from, to;  // (Kinematics column, weight)
  Eigen::Vector3d from_offset_mm = Eigen::Vector3d::Zero(), to_offset_mm = Eigen::Vector3d::Zero();
  double radius_from_mm = 0, radius_to_mm = 0;
  ClipMaterial material = ClipMaterial::kShirt;
};

class ClipBody {
 public:
  // InputError naming `source` when the skeleton lacks a CMU bone a shape needs, or for bad
  // options.
  ClipBody(const Skeleton& skeleton, const ClipBodyOptions& options, const std::string& source);

  const std::vector<ClipShape>& shapes() const { return shapes_; }
  // The shapes placed at joint positions (Kinematics::Compute's output, millimetres).
  void Place(const Eigen::Matrix3Xd& joint_in_world_mm, std::vector<Capsule>* capsules) const;
  // An end as text, for ground_truth.json: "lfemur", or "0.5 lhipjoint + 0.5 rhipjoint".
  std::string EndText(const std::vector<std::pair<int, double>>& end, const Eigen::Vector3d& offset_mm) const;

 private:
  std::vector<ClipShape> shapes_;
  std::vector<std::string> bone_names_;
};

}  // namespace jgpm
