// Biovision BVH files: a joint hierarchy with offsets and channels, then one line of
// channel values per frame.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "io/mocap/motion.h"
#include "io/mocap/rotation.h"

namespace jgpm {

enum class BvhChannel { kXposition, kYposition, kZposition, kXrotation, kYrotation, kZrotation };

std::string_view BvhChannelName(BvhChannel channel);  // "Xposition", ...

struct BvhJoint {
  std::string name;                // empty for an End Site
  int parent = -1;                 // index into Bvh::joints; -1 for the root
  Eigen::Vector3d offset{0, 0, 0}; // from the parent, parent frame, file units
  std::vector<BvhChannel> channels;
  bool end_site = false;
};

struct Bvh {
  std::vector<BvhJoint> joints;  // file order: parents before children
  RowMatrixXd frames;            // frames x NumChannels(), channels in joint order
  double frame_time = 1.0 / 120.0;
  // Millimetres per file unit. BVH does not store its unit; we write centimetres (what
  // Maya and MotionBuilder expect) and read centimetres unless told otherwise.
  double mm_per_unit = 10.0;

  int NumChannels() const;
  // Index of each joint's first channel in a frame row; size joints.size() + 1.
  std::vector<int> ChannelOffsets() const;
  int FindJoint(std::string_view name) const;  // -1 if absent
};

// Parses BVH text; throws InputError naming source:line and what was expected (bad
// hierarchy, unknown channels, wrong value counts, truncated frames, NaN...).
Bvh ParseBvh(std::string_view text, const std::string& source, double mm_per_unit = 10.0);
Bvh ReadBvh(const std::filesystem::path& path, double mm_per_unit = 10.0);

// Numbers are written with the fewest digits that read back to the same double.
std::string FormatBvh(const Bvh& bvh);
void WriteBvh(const std::filesystem::path& path, const Bvh& bvh);

// BVH forward kinematics for one frame: a joint's rotation is the product of its rotation
// channels in the listed order (e.g. "Zrotation Xrotation Yrotation": Rz Rx Ry), its
// translation the offset plus any position channels. Column j of `joint_in_world_mm` is
// joint j's position; `rotations`, when given, receives the global rotation of each joint.
void ComputeBvhPose(const Bvh& bvh, int frame, Eigen::Matrix3Xd* joint_in_world_mm,
                    std::vector<Eigen::Matrix3d>* rotations = nullptr);

}  // namespace jgpm
