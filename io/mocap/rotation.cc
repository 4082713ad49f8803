#include "io/mocap/rotation.h"

#include <cctype>
#include <algorithm>
#include <cmath>

#include "io/base/error.h"

namespace jgpm {

char AxisName(Axis axis) { return "xyz"[static_cast<int>(axis)]; }

bool ParseAxisOrder(std::string_view text, AxisOrder* order) {
  if (text.size() != 3) return false;
  bool seen[3] = {false, false, false};
  for (int i = 0; i < 3; ++i) {
    const int a = std::tolower(static_cast<unsigned char>(text[i])) - 'x';
    if (a < 0 || a > 2 || seen[a]) return false;
    seen[a] = true;
    (*order)[i] = static_cast<Axis>(a);
  }
  return true;
}

std::string AxisOrderName(const AxisOrder& order) {
  std::string name;
  for (Axis a : order) name += static_cast<char>(std::toupper(AxisName(a)));
  return name;
}

Eigen::Matrix3d AxisRotation(Axis axis, double angle_deg) {
  const double a = angle_deg * kDegToRad;
  const double c = std::cos(a), s = std::sin(a);
  Eigen::Matrix3d r;
  switch (axis) {
    case Axis::kX: r << 1, 0, 0, 0, c, -s, 0, s, c; break;
    case Axis::kY: r << c, 0, s, 0, 1, 0, -s, 0, c; break;
    case Axis::kZ: r << c, -s, 0, s, c, 0, 0, 0, 1; break;
  }
  return r;
}

Eigen::Matrix3d EulerToMatrix(const AxisOrder& order, const Eigen::Vector3d& angles_deg) {
  return AxisRotation(order[2], angles_deg[2]) * AxisRotation(order[1], angles_deg[1]) *
         AxisRotation(order[0], angles_deg[0]);
}

Eigen::Vector3d MatrixToEuler(const AxisOrder& order, const Eigen::Matrix3d& r) {
  // For R = R_k(c) R_j(b) R_i(a) with (i, j, k) a permutation of (x, y, z) and e = +1 when
  // the permutation is cyclic, -1 otherwise:
  //   R[k][i] = -e sin b,  (R[k][j], R[k][k]) ~ (e sin a, cos a),  (R[j][i], R[i][i]) ~ (e sin c, cos c).
  const int i = static_cast<int>(order[0]);
  const int j = static_cast<int>(order[1]);
  const int k = static_cast<int>(order[2]);
  JGPM_CHECK(i != j && j != k && i != k);
  const double e = ((j - i + 3) % 3 == 1) ? 1.0 : -1.0;
  const double cos_b = std::hypot(r(i, i), r(j, i));
  const double b = std::atan2(-e * r(k, i), cos_b);
  double a = 0, c = 0;
  if (cos_b > 1e-12) {
    a = std::atan2(e * r(k, j), r(k, k));
    c = std::atan2(e * r(j, i), r(i, i));
  } else {
    // Gimbal lock: only a +/- c is defined; put it all in a.
    a = std::atan2(-e * r(j, k), r(j, j));
  }
  return Eigen::Vector3d(a, b, c) * kRadToDeg;
}

double RotationToAngles(const Eigen::Matrix3d& m, std::span<const Axis> axes,
                        std::vector<double>* angles) {
  angles->clear();
  if (axes.empty()) {
    const double cos_angle = std::clamp((m.trace() - 1.0) / 2.0, -1.0, 1.0);
    return std::acos(cos_angle) * kRadToDeg;
  }
  auto other = [&](Axis a, Axis b) {
    for (int i = 0; i < 3; ++i) {
      if (static_cast<Axis>(i) != a && static_cast<Axis>(i) != b) return static_cast<Axis>(i);
    }
    return a;
  };
  AxisOrder order;
  if (axes.size() == 3) {
    order = {axes[0], axes[1], axes[2]};
  } else if (axes.size() == 2) {
    order = {axes[0], other(axes[0], axes[1]), axes[1]};  // unused axis in the middle, angle 0
  } else {
    const Axis second = other(axes[0], axes[0]);
    order = {axes[0], second, other(axes[0], second)};
  }
  const Eigen::Vector3d euler = MatrixToEuler(order, m);
  if (axes.size() == 3) {
    *angles = {euler[0], euler[1], euler[2]};
    return 0;
  }
  if (axes.size() == 2) {
    *angles = {euler[0], euler[2]};
    return std::abs(euler[1]);
  }
  *angles = {euler[0]};
  return std::max(std::abs(euler[1]), std::abs(euler[2]));
}

void UnwrapDegrees(std::span<double> angles_deg) {
  for (size_t t = 1; t < angles_deg.size(); ++t) {
    const double step = angles_deg[t] - angles_deg[t - 1];
    angles_deg[t] -= 360.0 * std::round(step / 360.0);
  }
}

double WrapDegrees(double angle_deg) {
  double wrapped = std::fmod(angle_deg, 360.0);
  if (wrapped > 180.0) wrapped -= 360.0;
  if (wrapped <= -180.0) wrapped += 360.0;
  return wrapped;
}

}  // namespace jgpm
