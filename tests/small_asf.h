// A small ASF skeleton written for the tests and fuzz seeds (not CMU data): root, a 2-bone
// leg with a bent local axis, and a spine bone. Units: length 0.45 (CMU's), degrees.
//   root   order TX TY TZ RX RY RZ, axis XYZ
//   hip    direction (1,0,0)  length 2, axis 0 0 0 XYZ,  no dofs
//   thigh  direction (0,-1,0) length 4, axis 0 0 90 XYZ, dof rx rz
//   shin   direction (0,-1,0) length 3, axis 0 0 0 XYZ,  dof rx
//   spine  direction (0,1,0)  length 5, axis 0 0 0 XYZ,  dof rx ry rz
#pragma once

#include <string>

namespace jgpm::test {

inline const char* SmallAsfText() {
  return R"(# test skeleton
:version 1.10
:name TEST
:units
  mass 1.0
  length 0.45
  angle deg
:documentation
  written by the jgpm tests
:root
   order TX TY TZ RX RY RZ
   axis XYZ
   position 0 0 0
   orientation 0 0 0
:bonedata
  begin
     id 1
     name hip
     direction 1 0 0
     length 2
     axis 0 0 0  XYZ
  end
  begin
     id 2
     name thigh
     direction 0 -1 0
     length 4
     axis 0 0 90  XYZ
    dof rx rz
    limits (-160.0 20.0)
           (-70.0 70.0)
  end
  begin
     id 3
     name shin
     direction 0 -1 0
     length 3
     axis 0 0 0  XYZ
    dof rx
    limits (-10.0 170.0)
  end
  begin
     id 4
     name spine
     direction 0 1 0
     length 5
     axis 0 0 0 XYZ
    dof rx ry rz
    limits (-inf inf)
           (-30 30) (-30 30)
  end
:hierarchy
  begin
    root hip spine
    hip thigh
    thigh shin
  end
)";
}

// A made-up skeleton with every bone of the 18 gait joints (io/gait/gait_pose.h) and the CMU
// bones' names and dofs, but its own simple geometry (not CMU data): for model files in
// fuzz seeds and tests that need a gait skeleton without reading the data root.
inline std::string GaitAsfText() {
  struct B {
    const char* name;
    const char* direction;
    double length;
    const char* dofs;
  };
  static const B bones[] = {
      {"lowerback", "0 1 0", 2, "rx ry rz"}, {"upperback", "0 1 0", 2, "rx ry rz"},
      {"thorax", "0 1 0", 2, "rx ry rz"},    {"lowerneck", "0 1 0", 1, "rx ry rz"},
      {"upperneck", "0 1 0", 1, "rx ry rz"}, {"head", "0 1 0", 1.5, "rx ry rz"},
      {"lfemur", "0.3 -0.95 0", 7, "rx ry rz"}, {"ltibia", "0 -1 0", 7, "rx"},
      {"lfoot", "0 0 1", 2, "rx rz"},        {"lhumerus", "1 0 0", 5, "rx ry rz"},
      {"lradius", "1 0 0", 4, "rx"},         {"lwrist", "1 0 0", 1, "ry"},
      {"rfemur", "-0.3 -0.95 0", 7, "rx ry rz"}, {"rtibia", "0 -1 0", 7, "rx"},
      {"rfoot", "0 0 1", 2, "rx rz"},        {"rhumerus", "-1 0 0", 5, "rx ry rz"},
      {"rradius", "-1 0 0", 4, "rx"},        {"rwrist", "-1 0 0", 1, "ry"},
  };
  std::string text =
      "# a made-up gait skeleton (jgpm tests)\n:version 1.10\n:name VICON\n:units\n  mass 1.0\n  length 0.45\n"
      "  angle deg\n:documentation\n  written by the jgpm tests\n:root\n   order TX TY TZ RX RY RZ\n   axis XYZ\n"
      "   position 0 0 0\n   orientation 0 0 0\n:bonedata\n";
  int id = 1;
  for (const B& b : bones) {
    text += "  begin\n     id " + std::to_string(id++) + "\n     name " + b.name + "\n     direction " + b.direction +
            "\n     length " + std::to_string(b.length) + "\n     axis 0 0 0  XYZ\n    dof " + b.dofs + "\n    limits";
    const std::string dofs = b.dofs;
    const int n = static_cast<int>((dofs.size() + 1) / 3);
    for (int i = 0; i < n; ++i) text += " (-180.0 180.0)";
    text += "\n  end\n";
  }
  text +=
      ":hierarchy\n  begin\n    root lowerback lfemur rfemur\n    lowerback upperback\n    upperback thorax\n"
      "    thorax lowerneck lhumerus rhumerus\n    lowerneck upperneck\n    upperneck head\n    lfemur ltibia\n"
      "    ltibia lfoot\n    lhumerus lradius\n    lradius lwrist\n    rfemur rtibia\n    rtibia rfoot\n"
      "    rhumerus rradius\n    rradius rwrist\n  end\n";
  return text;
}

}  // namespace jgpm::test
