#include "io/mocap/bvh_conversion.h"

#include <cmath>

#include "io/base/error.h"
#include "io/mocap/kinematics.h"

namespace jgpm {
namespace {

const std::vector<BvhChannel> kRotationChannels = {BvhChannel::kZrotation, BvhChannel::kYrotation,
                                                   BvhChannel::kXrotation};
// "Zrotation Yrotation Xrotation" is R = Rz Ry Rx: x applied first.
constexpr AxisOrder kBvhOrder = {Axis::kX, Axis::kY, Axis::kZ};

void UnwrapAngleColumns(const std::vector<bool>& is_angle, RowMatrixXd* values) {
  for (int c = 0; c < values->cols(); ++c) {
    if (!is_angle[c]) continue;
    Eigen::VectorXd column = values->col(c);
    UnwrapDegrees(std::span<double>(column.data(), column.size()));
    values->col(c) = column;
  }
}

}  // namespace

Bvh AcclaimToBvh(const Skeleton& skeleton, const Motion& motion, double mm_per_unit) {
  JGPM_CHECK(mm_per_unit > 0 && motion.values.cols() == skeleton.NumChannels());
  const double scale = skeleton.MillimetresPerUnit() / mm_per_unit;
  const int num_bones = static_cast<int>(skeleton.bones.size());
  auto bone_vector = [&](int b) -> Eigen::Vector3d {
    return skeleton.bones[b].direction * skeleton.bones[b].length * scale;
  };

  // Depth-first pre-order, as BVH nesting requires; End Sites right after leaf bones.
  Bvh bvh;
  bvh.mm_per_unit = mm_per_unit;
  bvh.frame_time = 1.0 / motion.frames_per_second;
  std::vector<int> joint_of_bone(num_bones, -1);
  std::vector<int> stack{0};
  while (!stack.empty()) {
    const int b = stack.back();
    stack.pop_back();
    const Bone& bone = skeleton.bones[b];
    BvhJoint joint;
    joint.name = bone.name;
    if (bone.parent >= 0) {
      joint.parent = joint_of_bone[bone.parent];
      joint.offset = bone_vector(bone.parent);
    } else {
      joint.channels = {BvhChannel::kXposition, BvhChannel::kYposition, BvhChannel::kZposition};
    }
    joint.channels.insert(joint.channels.end(), kRotationChannels.begin(), kRotationChannels.end());
    joint_of_bone[b] = static_cast<int>(bvh.joints.size());
    bvh.joints.push_back(std::move(joint));
    if (bone.children.empty()) {
      BvhJoint site;
      site.end_site = true;
      site.parent = joint_of_bone[b];
      site.offset = bone_vector(b);
      bvh.joints.push_back(std::move(site));
    }
    for (auto it = bone.children.rbegin(); it != bone.children.rend(); ++it) stack.push_back(*it);
  }

  const std::vector<int> bvh_offsets = bvh.ChannelOffsets();
  const std::vector<int> amc_offsets = skeleton.ChannelOffsets();
  const Kinematics kinematics(skeleton);
  bvh.frames.resize(motion.NumFrames(), bvh.NumChannels());
  Eigen::Matrix3Xd joints;
  std::vector<Eigen::Matrix3d> rotations;
  for (int f = 0; f < motion.NumFrames(); ++f) {
    kinematics.Compute(motion.Frame(f), &joints, &rotations);
    for (int b = 0; b < num_bones; ++b) {
      const Bone& bone = skeleton.bones[b];
      const int j = joint_of_bone[b];
      int c = bvh_offsets[j];
      Eigen::Matrix3d local = rotations[b];
      if (bone.parent >= 0) {
        local = rotations[bone.parent].transpose() * rotations[b];
      } else {
        Eigen::Vector3d position = skeleton.root_position;
        for (size_t d = 0; d < bone.dofs.size(); ++d) {
          if (!IsRotation(bone.dofs[d])) {
            position[static_cast<int>(DofAxis(bone.dofs[d]))] += motion.values(f, amc_offsets[b] + d);
          }
        }
        for (int i = 0; i < 3; ++i) bvh.frames(f, c++) = position[i] * scale;
      }
      const Eigen::Vector3d xyz = MatrixToEuler(kBvhOrder, local);
      bvh.frames(f, c) = xyz[2];
      bvh.frames(f, c + 1) = xyz[1];
      bvh.frames(f, c + 2) = xyz[0];
    }
  }
  // Continuous channels, so animation tools interpolate without 360-degree spins.
  std::vector<bool> is_angle(bvh.frames.cols(), true);
  for (int c = 0; c < 3; ++c) is_angle[c] = false;  // the root's position channels
  UnwrapAngleColumns(is_angle, &bvh.frames);
  return bvh;
}

std::vector<int> BvhJointToAcclaimColumn(const Bvh& bvh, const Skeleton& skeleton) {
  std::vector<int> column(bvh.joints.size(), -1);
  for (size_t j = 0; j < bvh.joints.size(); ++j) {
    const BvhJoint& joint = bvh.joints[j];
    const std::string& name = joint.end_site ? bvh.joints[joint.parent].name : joint.name;
    const int b = skeleton.FindBone(name);
    if (b < 0) continue;
    column[j] = joint.end_site ? b : std::max(skeleton.bones[b].parent, 0);
  }
  return column;
}

Motion BvhToAcclaim(const Bvh& bvh, const Skeleton& skeleton, const std::string& source) {
  const int num_bones = static_cast<int>(skeleton.bones.size());
  const double scale = skeleton.MillimetresPerUnit() / bvh.mm_per_unit;
  std::vector<int> joint_of_bone(num_bones);
  std::vector<Eigen::Matrix3d> c(num_bones);  // each bone's C
  for (int b = 0; b < num_bones; ++b) {
    const Bone& bone = skeleton.bones[b];
    c[b] = EulerToMatrix(bone.axis_order, bone.axis_deg);
    const int j = bvh.FindJoint(bone.name);
    if (j < 0) ThrowInputError(source, "no joint '" + bone.name + "' for the ASF bone of that name");
    joint_of_bone[b] = j;
    const BvhJoint& joint = bvh.joints[j];
    if (bone.parent < 0) {
      if (joint.parent >= 0) ThrowInputError(source, "joint '" + bone.name + "' must be the ROOT");
      continue;
    }
    const std::string& parent_name = skeleton.bones[bone.parent].name;
    if (joint.parent < 0 || bvh.joints[joint.parent].name != parent_name) {
      ThrowInputError(source, "joint '" + bone.name + "' must be a child of '" + parent_name +
                                  "' as in the ASF hierarchy");
    }
    const Eigen::Vector3d expected =
        skeleton.bones[bone.parent].direction * skeleton.bones[bone.parent].length * scale;
    if ((joint.offset - expected).norm() > 1e-3 * std::max(1.0, expected.norm())) {
      ThrowInputError(source, "joint '" + bone.name + "' OFFSET does not match the ASF bone '" +
                                  parent_name + "' (different skeleton or BVH unit?)");
    }
    for (BvhChannel channel : joint.channels) {
      if (channel <= BvhChannel::kZposition) {
        ThrowInputError(source, "joint '" + bone.name +
                                    "' has position channels; the ASF bone can only rotate");
      }
    }
  }

  Motion motion;
  motion.frames_per_second = 1.0 / bvh.frame_time;
  const int frames = static_cast<int>(bvh.frames.rows());
  motion.values.resize(frames, skeleton.NumChannels());
  const std::vector<int> offsets = skeleton.ChannelOffsets();
  Eigen::Matrix3Xd positions;
  std::vector<Eigen::Matrix3d> global;
  std::vector<double> angles;
  for (int f = 0; f < frames; ++f) {
    ComputeBvhPose(bvh, f, &positions, &global);
    for (int b = 0; b < num_bones; ++b) {
      const Bone& bone = skeleton.bones[b];
      const int j = joint_of_bone[b];
      const Eigen::Matrix3d local =
          bone.parent < 0 ? global[j] : global[joint_of_bone[bone.parent]].transpose() * global[j];
      const double residual =
          RotationToAngles(c[b].transpose() * local * c[b], RotationAxes(bone), &angles);
      if (residual > 1e-3) {
        ThrowInputError(source, "frame " + std::to_string(f + 1) + ": joint '" + bone.name +
                                    "' rotates " + std::to_string(residual) +
                                    " degrees about an axis its ASF bone has no dof for");
      }
      Eigen::Vector3d translation = Eigen::Vector3d::Zero();
      if (bone.parent < 0) translation = positions.col(j) / skeleton.MillimetresPerUnit() -
                                         skeleton.root_position;
      size_t next_angle = 0;
      for (size_t d = 0; d < bone.dofs.size(); ++d) {
        double& value = motion.values(f, offsets[b] + d);
        if (IsRotation(bone.dofs[d])) {
          value = angles[next_angle++];
        } else {
          const int axis = static_cast<int>(DofAxis(bone.dofs[d]));
          value = translation[axis];
          translation[axis] = 0;
        }
      }
      if (translation.norm() * skeleton.MillimetresPerUnit() > 1e-6) {
        ThrowInputError(source, "frame " + std::to_string(f + 1) +
                                    ": the root moves along an axis the ASF root has no "
                                    "translation dof for");
      }
    }
  }
  std::vector<bool> is_angle;
  for (const Bone& bone : skeleton.bones) {
    for (Dof dof : bone.dofs) is_angle.push_back(IsRotation(dof));
  }
  UnwrapAngleColumns(is_angle, &motion.values);
  return motion;
}

}  // namespace jgpm
