#include "tracker/state/state_model.h"

#include <algorithm>
#include <cmath>

#include "io/base/error.h"

namespace jgpm {

void StateModel::Diffuse(double scale, Random* random, double* state) const {
  const Eigen::VectorXd std = DiffusionStd();
  for (int d = 0; d < Dimension(); ++d) state[d] += scale * std[d] * random->Normal();
  Normalise(state);
}

double StateModel::Period(int) const { return 0; }

PosePlacer::PosePlacer(const Skeleton& skeleton)
    : layout_(skeleton, "the model's skeleton"), kinematics_(skeleton), limbs_(skeleton) {
  feet_ = skeleton.FootBones();
  if (feet_.empty()) ThrowInputError("the model's skeleton", "has no lfoot, rfoot, ltoes or rtoes bone to stand on");
}

void PosePlacer::Relative(const double* pose, Eigen::Matrix3Xd* relative, double* foot_height_mm) const {
  Relative(pose, proportions_, relative, foot_height_mm);
}

void PosePlacer::Relative(const double* pose, const Proportions& proportions, Eigen::Matrix3Xd* relative,
                          double* foot_height_mm) const {
  thread_local std::vector<double> frame;
  frame.resize(kinematics_.NumChannels());
  layout_.ToFrame(pose, frame.data());
  kinematics_.Compute(frame.data(), relative);
  const Eigen::Vector3d root = relative->col(0);
  relative->colwise() -= root;
  double foot = 1e300;
  for (int b : feet_) foot = std::min(foot, (*relative)(1, b));
  *foot_height_mm = foot;
  limbs_.Apply(proportions, relative, foot_height_mm);
}

void PosePlacer::Place(const double* pose, double x_mm, double z_mm, double heading_rad, double size,
                       Eigen::Matrix3Xd* world) const {
  Place(pose, x_mm, z_mm, heading_rad, size, proportions_, floor_mm_, world);
}

void PosePlacer::Place(const double* pose, double x_mm, double z_mm, double heading_rad, double size,
                       const Proportions& proportions, double floor_mm, Eigen::Matrix3Xd* world) const {
  thread_local Eigen::Matrix3Xd relative;
  double foot = 0;
  Relative(pose, proportions, &relative, &foot);
  PlaceInWorld(relative, foot, x_mm, z_mm, heading_rad, size, kFootClearanceMm + floor_mm, world);
}

void PlaceInWorld(const Eigen::Matrix3Xd& relative, double foot_height_mm, double x_mm, double z_mm,
                  double heading_rad, double size, double clearance_mm, Eigen::Matrix3Xd* world) {
  const double c = std::cos(heading_rad), s = std::sin(heading_rad);
  const double root_y = clearance_mm - size * foot_height_mm;
  world->resize(3, relative.cols());
  for (int b = 0; b < relative.cols(); ++b) {
    const double x = size * relative(0, b), y = size * relative(1, b), z = size * relative(2, b);
    (*world)(0, b) = x_mm + c * x + s * z;
    (*world)(1, b) = root_y + y;
    (*world)(2, b) = z_mm - s * x + c * z;
  }
}

}  // namespace jgpm
