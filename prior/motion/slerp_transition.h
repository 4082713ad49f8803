// SLERP in-betweening, the animation tools' standard and issue #16's baseline for LSOPA:
// frames between two poses of one skeleton (AMC dof values), the root's translation
// interpolated linearly and every bone's rotation by quaternion slerp along the shorter
// arc, at constant angular speed.
//
// A bone's rotation here is its dof rotation M (the product of its rotation dofs in dof
// order, Acclaim's convention): its world rotation R_parent C M C^T only conjugates M by
// the constant C, which maps geodesics to geodesics, so slerping M is slerping the bone's
// rotation relative to its parent. The slerped M goes back to the bone's own dofs
// (io/mocap/rotation.h RotationToAngles); for a bone with fewer than three rotation dofs (a
// knee) slerp between two rotations about one axis stays on it, and for two dofs the part
// the dofs cannot express is dropped. Each angle is taken the way round nearest the frame
// before (for three dofs, also the nearer of the two Euler solutions), so channels do not
// jump by 360 degrees or flip branch.
#pragma once

#include <Eigen/Core>

#include "io/mocap/motion.h"
#include "io/mocap/skeleton.h"

namespace jgpm {

// The pose a fraction t in [0, 1] of the way from `from` to `to` (rows of NumChannels()
// values); `near` is the frame the angles continue from (typically the frame before).
Eigen::RowVectorXd SlerpPose(const Skeleton& skeleton, const Eigen::RowVectorXd& from, const Eigen::RowVectorXd& to,
                             double t, const Eigen::RowVectorXd& near);

// The `frames` poses strictly between `from` and `to`, at t = i / (frames + 1).
// InputError for frames < 1, sizes that do not match the skeleton, or non-finite values.
RowMatrixXd SlerpTransition(const Skeleton& skeleton, const Eigen::RowVectorXd& from, const Eigen::RowVectorXd& to,
                            int frames);

}  // namespace jgpm
