// A small ASF skeleton written for the tests and fuzz seeds (not CMU data): root, a 2-bone
// leg with a bent local axis, and a spine bone. Units: length 0.45 (CMU's), degrees.
//   root   order TX TY TZ RX RY RZ, axis XYZ
//   hip    direction (1,0,0)  length 2, axis 0 0 0 XYZ,  no dofs
//   thigh  direction (0,-1,0) length 4, axis 0 0 90 XYZ, dof rx rz
//   shin   direction (0,-1,0) length 3, axis 0 0 0 XYZ,  dof rx
//   spine  direction (0,1,0)  length 5, axis 0 0 0 XYZ,  dof rx ry rz
#pragma once

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

}  // namespace jgpm::test
