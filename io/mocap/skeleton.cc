#include "io/mocap/skeleton.h"

#include <cctype>

namespace jgpm {

std::string_view DofName(Dof dof) {
  static constexpr std::string_view kNames[] = {"rx", "ry", "rz", "tx", "ty", "tz"};
  return kNames[static_cast<int>(dof)];
}

bool ParseDof(std::string_view text, Dof* dof) {
  if (text.size() != 2) return false;
  const char kind = static_cast<char>(std::tolower(static_cast<unsigned char>(text[0])));
  const int axis = std::tolower(static_cast<unsigned char>(text[1])) - 'x';
  if ((kind != 'r' && kind != 't') || axis < 0 || axis > 2) return false;
  *dof = static_cast<Dof>((kind == 'r' ? 0 : 3) + axis);
  return true;
}

std::vector<Axis> RotationAxes(const Bone& bone) {
  std::vector<Axis> axes;
  for (Dof dof : bone.dofs) {
    if (IsRotation(dof)) axes.push_back(DofAxis(dof));
  }
  return axes;
}

int Skeleton::FindBone(std::string_view bone_name) const {
  for (size_t i = 0; i < bones.size(); ++i) {
    if (bones[i].name == bone_name) return static_cast<int>(i);
  }
  return -1;
}

std::vector<int> Skeleton::FootBones() const {
  std::vector<int> feet;
  for (const char* name : {"lfoot", "rfoot", "ltoes", "rtoes"}) {
    if (const int b = FindBone(name); b >= 0) feet.push_back(b);
  }
  return feet;
}

int Skeleton::NumChannels() const {
  int n = 0;
  for (const Bone& bone : bones) n += static_cast<int>(bone.dofs.size());
  return n;
}

std::vector<int> Skeleton::ChannelOffsets() const {
  std::vector<int> offsets(bones.size() + 1, 0);
  for (size_t i = 0; i < bones.size(); ++i) {
    offsets[i + 1] = offsets[i] + static_cast<int>(bones[i].dofs.size());
  }
  return offsets;
}

std::vector<std::string> Skeleton::ChannelNames() const {
  std::vector<std::string> names;
  for (const Bone& bone : bones) {
    for (Dof dof : bone.dofs) names.push_back(bone.name + "." + std::string(DofName(dof)));
  }
  return names;
}

std::vector<std::string> Skeleton::BoneNames() const {
  std::vector<std::string> names;
  for (const Bone& bone : bones) names.push_back(bone.name);
  return names;
}

}  // namespace jgpm
