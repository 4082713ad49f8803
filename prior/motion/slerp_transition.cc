#include "prior/motion/slerp_transition.h"

#include <cmath>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "io/base/error.h"
#include "io/mocap/rotation.h"

namespace jgpm {
namespace {

// M = R(dof_k) ... R(dof_0): the first dof's rotation applied first.
Eigen::Matrix3d DofRotation(const std::vector<Axis>& axes, const double* angles_deg) {
  Eigen::Matrix3d m = Eigen::Matrix3d::Identity();
  for (size_t k = 0; k < axes.size(); ++k) m = AxisRotation(axes[k], angles_deg[k]) * m;
  return m;
}

}  // namespace

Eigen::RowVectorXd SlerpPose(const Skeleton& skeleton, const Eigen::RowVectorXd& from, const Eigen::RowVectorXd& to,
                             double t, const Eigen::RowVectorXd& near) {
  const int channels = skeleton.NumChannels();
  JGPM_CHECK(from.size() == channels && to.size() == channels && near.size() == channels);
  const std::vector<int> offsets = skeleton.ChannelOffsets();
  Eigen::RowVectorXd pose = near;
  for (size_t b = 0; b < skeleton.bones.size(); ++b) {
    const Bone& bone = skeleton.bones[b];
    std::vector<Axis> axes;
    std::vector<int> columns;  // of the rotation dofs, in dof order
    for (size_t k = 0; k < bone.dofs.size(); ++k) {
      const int column = offsets[b] + static_cast<int>(k);
      if (IsRotation(bone.dofs[k])) {
        axes.push_back(DofAxis(bone.dofs[k]));
        columns.push_back(column);
      } else {
        pose(column) = (1 - t) * from(column) + t * to(column);  // the root's translation
      }
    }
    if (axes.empty()) continue;
    std::vector<double> a, z;
    for (int c : columns) a.push_back(from(c)), z.push_back(to(c));
    const Eigen::Quaterniond qa(DofRotation(axes, a.data())), qz(DofRotation(axes, z.data()));
    const Eigen::Matrix3d m = qa.slerp(t, qz).toRotationMatrix();  // Eigen takes the shorter arc
    std::vector<double> angles;
    RotationToAngles(m, axes, &angles);
    // Three angles have a second solution (first + 180, 180 - middle, last + 180): take the
    // one nearer `near`, each angle the way round nearest it.
    auto continued = [&](const std::vector<double>& solution, double* distance) {
      std::vector<double> out(solution.size());
      *distance = 0;
      for (size_t k = 0; k < solution.size(); ++k) {
        const double previous = near(columns[k]);
        out[k] = previous + WrapDegrees(solution[k] - previous);
        *distance += std::abs(out[k] - previous);
      }
      return out;
    };
    double distance;
    std::vector<double> chosen = continued(angles, &distance);
    if (angles.size() == 3) {
      const std::vector<double> other = {angles[0] + 180, 180 - angles[1], angles[2] + 180};
      double other_distance;
      const std::vector<double> alternative = continued(other, &other_distance);
      if (other_distance < distance && (DofRotation(axes, other.data()) - m).cwiseAbs().maxCoeff() < 1e-9) {
        chosen = alternative;
      }
    }
    for (size_t k = 0; k < columns.size(); ++k) pose(columns[k]) = chosen[k];
  }
  return pose;
}

RowMatrixXd SlerpTransition(const Skeleton& skeleton, const Eigen::RowVectorXd& from, const Eigen::RowVectorXd& to,
                            int frames) {
  if (frames < 1) ThrowInputError("slerp transition", "frames must be >= 1, got " + std::to_string(frames));
  const int channels = skeleton.NumChannels();
  if (from.size() != channels || to.size() != channels) {
    ThrowInputError("slerp transition", "poses have " + std::to_string(from.size()) + " and " +
                                            std::to_string(to.size()) + " values; the skeleton has " +
                                            std::to_string(channels) + " channels");
  }
  if (!from.allFinite() || !to.allFinite()) ThrowInputError("slerp transition", "a pose holds a non-finite value");
  RowMatrixXd out(frames, channels);
  Eigen::RowVectorXd near = from;
  for (int i = 1; i <= frames; ++i) {
    near = SlerpPose(skeleton, from, to, static_cast<double>(i) / (frames + 1), near);
    out.row(i - 1) = near;
  }
  return out;
}

}  // namespace jgpm
