// The pose representation of the gait models (paper section VI-A): 18 joints as joint-angle
// channels, without the root's translation and with its global heading removed, so that
// gaits recorded in different places and directions compare.
//
// The 18 joints: root, lowerback, upperback, thorax, neck, head, and left/right femur,
// tibia, foot, humerus, radius, wrist. The paper's "neck" is CMU's two neck bones
// (lowerneck + upperneck): their rotations nearly cancel in CMU data, so keeping only one
// would tilt the head by up to 25 degrees. All other bones (hip joints, clavicles, hands,
// fingers, thumbs, toes) are held at zero. On the CMU skeleton this gives 43 channels.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "io/mocap/kinematics.h"
#include "io/mocap/skeleton.h"

namespace jgpm {

struct GaitJoint {
  std::string_view name;
  std::vector<std::string_view> bones;  // CMU bones whose dofs the joint carries
};

// The 18 joints, root first.
const std::vector<GaitJoint>& GaitJoints();

class GaitPoseLayout {
 public:
  // InputError (naming `source`) if the skeleton lacks one of the joints' bones.
  GaitPoseLayout(const Skeleton& skeleton, const std::string& source);

  int NumChannels() const { return static_cast<int>(skeleton_channel_.size()); }
  // The skeleton's file (for errors about it).
  const std::string& source() const { return source_; }
  // "lfemur.rx"-style names.
  const std::vector<std::string>& channel_names() const { return names_; }
  // Index into the skeleton's frame vector of each channel.
  const std::vector<int>& skeleton_channels() const { return skeleton_channel_; }
  // GaitJoints() index of each channel.
  const std::vector<int>& channel_joints() const { return channel_joint_; }
  // For joints 1..17 (all but the root), the Kinematics column that stands for the joint:
  // the end of its last bone (femur -> knee, tibia -> ankle, ..., head -> top of head).
  const std::vector<int>& measured_columns() const { return measured_columns_; }

  // The root's rotation relative to the rest pose in a skeleton frame.
  Eigen::Matrix3d RootRotation(const double* frame) const;

  // Skeleton frame -> pose channels, with the heading `heading_deg` (a rotation about the
  // vertical y axis) taken out of the root rotation. Angles are wrapped to (-180, 180].
  void FromFrame(const double* frame, double heading_deg, double* pose) const;
  // Pose channels -> a skeleton frame at the origin facing +z; other channels zero.
  void ToFrame(const double* pose, double* frame) const;
  // The inverse of FromFrame: pose channels -> a skeleton frame turned by `heading_deg`
  // about +y, the root's translation dofs set to `root_translation` (skeleton units, x y z).
  void ToFrame(const double* pose, double heading_deg, const Eigen::Vector3d& root_translation, double* frame) const;

 private:
  std::string source_;
  std::vector<std::string> names_;
  std::vector<int> skeleton_channel_;
  std::vector<int> channel_joint_;
  std::vector<int> measured_columns_;
  int num_skeleton_channels_ = 0;
  Eigen::Matrix3d root_c_;                // root C
  std::vector<Axis> root_axes_;           // root rotation dofs, in order
  std::vector<int> root_frame_channels_;  // their indices in a skeleton frame
  std::vector<int> root_pose_channels_;   // and in a pose
  std::vector<std::pair<int, int>> root_translation_channels_;  // (frame index, coordinate)
};

// Joint positions of gait poses on one skeleton.
class GaitPoseKinematics {
 public:
  // InputError (naming `source`) if the skeleton lacks a gait joint's bone.
  GaitPoseKinematics(const Skeleton& skeleton, const std::string& source);

  const GaitPoseLayout& layout() const { return layout_; }
  // Positions in millimetres of the 17 measured joints (GaitJoints() 1..17, see
  // GaitPoseLayout::measured_columns) of a pose at the origin facing +z: 3 x 17.
  void Compute(const double* pose, Eigen::Matrix3Xd* joints) const;

 private:
  GaitPoseLayout layout_;
  Kinematics kinematics_;
};

// Heading (degrees about +y; 0 when facing +z, the CMU skeleton's forward direction) of a
// root rotation.
double HeadingOf(const Eigen::Matrix3d& root_rotation);

}  // namespace jgpm
