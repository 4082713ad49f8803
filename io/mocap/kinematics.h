// Forward kinematics of an Acclaim skeleton, following the ASF/AMC conventions:
//   C_b  = EulerToMatrix(axis_order, axis)       the bone's local frame at rest
//   M_b  = rotations of its dofs, applied in dof order (dof "rx ry rz": Rz Ry Rx)
//   R_b  = R_parent C_b M_b C_b^T                 its rotation relative to the rest pose
//   end_b = end_parent + R_b direction_b length_b
// The root's translation dofs are added to the `:root position`, and all lengths are
// converted to millimetres with Skeleton::MillimetresPerUnit().
#pragma once

#include <vector>

#include <Eigen/Core>

#include "io/mocap/motion.h"
#include "io/mocap/skeleton.h"

namespace jgpm {

class Kinematics {
 public:
  // Copies what it needs; the skeleton may be destroyed afterwards.
  explicit Kinematics(const Skeleton& skeleton);

  int NumBones() const { return static_cast<int>(bones_.size()); }
  int NumChannels() const { return num_channels_; }

  // Joint positions in millimetres for one frame of NumChannels() values: column b is the
  // end point of bone b (column 0, the root's position). `rotations`, when given, receives
  // every bone's R_b.
  void Compute(const double* frame, Eigen::Matrix3Xd* joint_in_world_mm,
               std::vector<Eigen::Matrix3d>* rotations = nullptr) const;
  Eigen::Matrix3Xd Compute(const double* frame) const;

 private:
  struct BoneData {
    int parent;
    int channel_offset;
    Eigen::Matrix3d c;                  // C_b
    Eigen::Vector3d offset_mm;          // direction * length in millimetres
    std::vector<std::pair<int, Axis>> rotation_dofs;     // (value index, axis)
    std::vector<std::pair<int, int>> translation_dofs;   // (value index, coordinate)
  };
  std::vector<BoneData> bones_;
  Eigen::Vector3d root_position_mm_;
  double mm_per_unit_;
  int num_channels_;
};

// Joint positions of every frame: element f is Kinematics::Compute of frame f.
std::vector<Eigen::Matrix3Xd> ComputeJointPositions(const Skeleton& skeleton, const Motion& motion);

}  // namespace jgpm
