#include "io/gait/gait_pose.h"

#include <cmath>

#include "io/base/error.h"

namespace jgpm {

const std::vector<GaitJoint>& GaitJoints() {
  static const std::vector<GaitJoint> joints = {
      {"root", {"root"}},         {"lowerback", {"lowerback"}},
      {"upperback", {"upperback"}}, {"thorax", {"thorax"}},
      {"neck", {"lowerneck", "upperneck"}}, {"head", {"head"}},
      {"lfemur", {"lfemur"}},     {"ltibia", {"ltibia"}},
      {"lfoot", {"lfoot"}},       {"lhumerus", {"lhumerus"}},
      {"lradius", {"lradius"}},   {"lwrist", {"lwrist"}},
      {"rfemur", {"rfemur"}},     {"rtibia", {"rtibia"}},
      {"rfoot", {"rfoot"}},       {"rhumerus", {"rhumerus"}},
      {"rradius", {"rradius"}},   {"rwrist", {"rwrist"}},
  };
  return joints;
}

GaitPoseLayout::GaitPoseLayout(const Skeleton& skeleton, const std::string& source)
    : source_(source), num_skeleton_channels_(skeleton.NumChannels()) {
  const std::vector<int> offsets = skeleton.ChannelOffsets();
  const std::vector<GaitJoint>& joints = GaitJoints();
  for (size_t j = 0; j < joints.size(); ++j) {
    int last_bone = -1;
    for (std::string_view bone_name : joints[j].bones) {
      const int b = skeleton.FindBone(bone_name);
      if (b < 0) {
        ThrowInputError(source, "skeleton has no bone '" + std::string(bone_name) +
                                    "', needed for the gait joint '" +
                                    std::string(joints[j].name) + "'");
      }
      const Bone& bone = skeleton.bones[b];
      for (size_t d = 0; d < bone.dofs.size(); ++d) {
        if (!IsRotation(bone.dofs[d])) {  // the root's translation is dropped
          if (b == 0) root_translation_channels_.push_back({offsets[b] + static_cast<int>(d), static_cast<int>(DofAxis(bone.dofs[d]))});
          continue;
        }
        const int channel = offsets[b] + static_cast<int>(d);
        if (b == 0) {
          root_axes_.push_back(DofAxis(bone.dofs[d]));
          root_frame_channels_.push_back(channel);
          root_pose_channels_.push_back(static_cast<int>(skeleton_channel_.size()));
        }
        names_.push_back(bone.name + "." + std::string(DofName(bone.dofs[d])));
        skeleton_channel_.push_back(channel);
        channel_joint_.push_back(static_cast<int>(j));
      }
      last_bone = b;
    }
    if (j > 0) measured_columns_.push_back(last_bone);
  }
  const Bone& root = skeleton.bones[0];
  root_c_ = EulerToMatrix(root.axis_order, root.axis_deg);
}

Eigen::Matrix3d GaitPoseLayout::RootRotation(const double* frame) const {
  Eigen::Matrix3d m = Eigen::Matrix3d::Identity();
  for (size_t i = 0; i < root_axes_.size(); ++i) {
    m = AxisRotation(root_axes_[i], frame[root_frame_channels_[i]]) * m;
  }
  return root_c_ * m * root_c_.transpose();
}

void GaitPoseLayout::FromFrame(const double* frame, double heading_deg, double* pose) const {
  for (int c = 0; c < NumChannels(); ++c) pose[c] = WrapDegrees(frame[skeleton_channel_[c]]);
  const Eigen::Matrix3d rotation =
      AxisRotation(Axis::kY, -heading_deg) * RootRotation(frame);
  std::vector<double> angles;
  RotationToAngles(root_c_.transpose() * rotation * root_c_, root_axes_, &angles);
  for (size_t i = 0; i < angles.size(); ++i) pose[root_pose_channels_[i]] = angles[i];
}

void GaitPoseLayout::ToFrame(const double* pose, double* frame) const {
  std::fill(frame, frame + num_skeleton_channels_, 0.0);
  for (int c = 0; c < NumChannels(); ++c) frame[skeleton_channel_[c]] = pose[c];
}

void GaitPoseLayout::ToFrame(const double* pose, double heading_deg, const Eigen::Vector3d& root_translation,
                             double* frame) const {
  ToFrame(pose, frame);
  const Eigen::Matrix3d rotation = AxisRotation(Axis::kY, heading_deg) * RootRotation(frame);
  std::vector<double> angles;
  RotationToAngles(root_c_.transpose() * rotation * root_c_, root_axes_, &angles);
  for (size_t i = 0; i < angles.size(); ++i) frame[root_frame_channels_[i]] = angles[i];
  for (const auto& [channel, coordinate] : root_translation_channels_) frame[channel] = root_translation[coordinate];
}

GaitPoseKinematics::GaitPoseKinematics(const Skeleton& skeleton, const std::string& source)
    : layout_(skeleton, source), kinematics_(skeleton) {}

void GaitPoseKinematics::Compute(const double* pose, Eigen::Matrix3Xd* joints) const {
  thread_local std::vector<double> frame;
  thread_local Eigen::Matrix3Xd all;
  frame.resize(kinematics_.NumChannels());
  layout_.ToFrame(pose, frame.data());
  kinematics_.Compute(frame.data(), &all);
  const std::vector<int>& columns = layout_.measured_columns();
  joints->resize(3, static_cast<int>(columns.size()));
  for (size_t j = 0; j < columns.size(); ++j) joints->col(j) = all.col(columns[j]);
}

double HeadingOf(const Eigen::Matrix3d& root_rotation) {
  const Eigen::Vector3d forward = root_rotation.col(2);
  return std::atan2(forward.x(), forward.z()) * kRadToDeg;
}

}  // namespace jgpm
