// Conversion between Acclaim (ASF skeleton + AMC motion) and BVH.
//
// Each ASF bone b becomes a BVH joint named after it, placed at the bone's start, with
// the bone's own rotation C_b M_b C_b^T as "Zrotation Yrotation Xrotation" channels (the
// CMU BVH convention); the root also gets "Xposition Yposition Zposition". A bone without
// children ends in an End Site at the bone's end, so every ASF joint position is a BVH
// joint or End Site position.
#pragma once

#include "io/mocap/bvh.h"
#include "io/mocap/motion.h"
#include "io/mocap/skeleton.h"

namespace jgpm {

// `mm_per_unit` is the unit of the written BVH (default centimetres).
Bvh AcclaimToBvh(const Skeleton& skeleton, const Motion& motion, double mm_per_unit = 10.0);

// Motion of `skeleton` that reproduces `bvh`. Joints are matched by name; the BVH
// hierarchy and offsets must be the skeleton's (to 1e-3 relative), and each joint may only
// rotate about the axes its bone has dofs for (to 1e-3 degrees). Throws InputError naming
// `source` and the joint or frame that does not fit.
Motion BvhToAcclaim(const Bvh& bvh, const Skeleton& skeleton, const std::string& source);

// For each BVH joint of AcclaimToBvh's output, the Kinematics column (bone end) at the
// same place: a joint sits at its bone's start, i.e. at the parent bone's end (the root
// at the root position); an End Site at its bone's end.
std::vector<int> BvhJointToAcclaimColumn(const Bvh& bvh, const Skeleton& skeleton);

}  // namespace jgpm
