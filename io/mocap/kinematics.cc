#include "io/mocap/kinematics.h"

#include "io/base/error.h"

namespace jgpm {

Kinematics::Kinematics(const Skeleton& skeleton)
    : root_position_mm_(skeleton.root_position * skeleton.MillimetresPerUnit()),
      mm_per_unit_(skeleton.MillimetresPerUnit()),
      num_channels_(skeleton.NumChannels()) {
  const std::vector<int> offsets = skeleton.ChannelOffsets();
  bones_.reserve(skeleton.bones.size());
  for (size_t b = 0; b < skeleton.bones.size(); ++b) {
    const Bone& bone = skeleton.bones[b];
    JGPM_CHECK(bone.parent < static_cast<int>(b));  // parents first (ParseAsf guarantees it)
    BoneData data;
    data.parent = bone.parent;
    data.channel_offset = offsets[b];
    data.c = EulerToMatrix(bone.axis_order, bone.axis_deg);
    data.offset_mm = bone.direction * bone.length * mm_per_unit_;
    for (size_t d = 0; d < bone.dofs.size(); ++d) {
      const int index = offsets[b] + static_cast<int>(d);
      if (IsRotation(bone.dofs[d])) {
        data.rotation_dofs.emplace_back(index, DofAxis(bone.dofs[d]));
      } else {
        data.translation_dofs.emplace_back(index, static_cast<int>(DofAxis(bone.dofs[d])));
      }
    }
    bones_.push_back(std::move(data));
  }
}

void Kinematics::Compute(const double* frame, Eigen::Matrix3Xd* joints,
                         std::vector<Eigen::Matrix3d>* rotations) const {
  const int n = NumBones();
  joints->resize(3, n);
  // R_b of every bone, kept in the caller's vector when asked for.
  std::vector<Eigen::Matrix3d> local_rotations;
  std::vector<Eigen::Matrix3d>& r = rotations ? *rotations : local_rotations;
  r.resize(n);
  for (int b = 0; b < n; ++b) {
    const BoneData& bone = bones_[b];
    Eigen::Matrix3d m = Eigen::Matrix3d::Identity();
    for (const auto& [index, axis] : bone.rotation_dofs) m = AxisRotation(axis, frame[index]) * m;
    const Eigen::Matrix3d local = bone.c * m * bone.c.transpose();
    if (bone.parent < 0) {
      r[b] = local;
      Eigen::Vector3d position = root_position_mm_;
      for (const auto& [index, coordinate] : bone.translation_dofs) {
        position[coordinate] += frame[index] * mm_per_unit_;
      }
      joints->col(b) = position + r[b] * bone.offset_mm;
    } else {
      r[b] = r[bone.parent] * local;
      joints->col(b) = joints->col(bone.parent) + r[b] * bone.offset_mm;
    }
  }
}

Eigen::Matrix3Xd Kinematics::Compute(const double* frame) const {
  Eigen::Matrix3Xd joints;
  Compute(frame, &joints);
  return joints;
}

std::vector<Eigen::Matrix3Xd> ComputeJointPositions(const Skeleton& skeleton, const Motion& motion) {
  const Kinematics kinematics(skeleton);
  JGPM_CHECK(motion.values.cols() == kinematics.NumChannels());
  std::vector<Eigen::Matrix3Xd> positions(motion.NumFrames());
  for (int f = 0; f < motion.NumFrames(); ++f) kinematics.Compute(motion.Frame(f), &positions[f]);
  return positions;
}

}  // namespace jgpm
