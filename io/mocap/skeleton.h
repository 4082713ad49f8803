// An Acclaim skeleton (the content of an ASF file): bones with their rest direction,
// length, local axis and degrees of freedom, arranged in a tree under the root.
#pragma once

#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "io/mocap/rotation.h"

namespace jgpm {

// One degree of freedom of a bone. Rotations are in degrees about the bone's local axes;
// translations (root only) in the skeleton's length units.
enum class Dof { kRx, kRy, kRz, kTx, kTy, kTz };

std::string_view DofName(Dof dof);  // "rx", ..., "tz"
bool ParseDof(std::string_view text, Dof* dof);  // case-insensitive
inline bool IsRotation(Dof dof) { return dof <= Dof::kRz; }
inline Axis DofAxis(Dof dof) { return static_cast<Axis>(static_cast<int>(dof) % 3); }

struct DofLimit {
  double min = -std::numeric_limits<double>::infinity();
  double max = std::numeric_limits<double>::infinity();
};

struct Bone {
  std::string name;
  int id = 0;                          // ASF id (0 for the root)
  Eigen::Vector3d direction{0, 0, 0};  // unit vector, world frame at rest
  double length = 0;                   // skeleton length units
  Eigen::Vector3d axis_deg{0, 0, 0};   // local frame C = EulerToMatrix(axis_order, axis_deg)
  AxisOrder axis_order{Axis::kX, Axis::kY, Axis::kZ};
  std::vector<Dof> dofs;               // in the order the AMC lists their values
  std::vector<DofLimit> limits;        // one per dof, or empty when the file gives none
  int parent = -1;                     // index into Skeleton::bones; -1 for the root
  std::vector<int> children;           // indices into Skeleton::bones, hierarchy order
};

// Axes of the bone's rotation dofs, in dof order.
std::vector<Axis> RotationAxes(const Bone& bone);

struct Skeleton {
  std::string name;
  std::string version;
  double mass = 1.0;
  // ASF `:units length`: file lengths are inches times this factor (the Acclaim/CMU
  // convention), so one unit is 25.4 / length_scale millimetres.
  double length_scale = 1.0;
  // bones[0] is the root: its dofs are the `:root order`, its axis the `:root axis` with
  // the `orientation` angles, and root_position its rest translation.
  std::vector<Bone> bones;
  Eigen::Vector3d root_position{0, 0, 0};

  double MillimetresPerUnit() const { return 25.4 / length_scale; }
  // Index of the bone with this name, or -1.
  int FindBone(std::string_view name) const;
  // The bones whose ends touch the floor (lfoot, rfoot, ltoes, rtoes), those it has.
  std::vector<int> FootBones() const;
  // Total number of dof values per frame (62 for the standard CMU skeleton).
  int NumChannels() const;
  // Index of each bone's first value in a frame vector (bones in skeleton order, each
  // bone's dofs in its dof order); size bones.size() + 1, the last entry NumChannels().
  std::vector<int> ChannelOffsets() const;
  // "lfemur.rx"-style names of the frame vector's values.
  std::vector<std::string> ChannelNames() const;
  // The bones' names, in skeleton order.
  std::vector<std::string> BoneNames() const;
};

}  // namespace jgpm
