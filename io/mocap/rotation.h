// Rotations as used by Acclaim (ASF/AMC) and BVH files: Euler angles in degrees about the
// fixed x, y, z axes, applied in a stated order.
#pragma once

#include <array>
#include <numbers>
#include <span>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace jgpm {

enum class Axis { kX = 0, kY = 1, kZ = 2 };

// Three distinct axes; the rotation about order[0] is applied first.
using AxisOrder = std::array<Axis, 3>;

constexpr double kDegToRad = std::numbers::pi / 180;
constexpr double kRadToDeg = 180 / std::numbers::pi;

char AxisName(Axis axis);  // 'x', 'y' or 'z'
// "XYZ"-style string (case-insensitive) -> order; false if it is not a permutation of XYZ.
bool ParseAxisOrder(std::string_view text, AxisOrder* order);
std::string AxisOrderName(const AxisOrder& order);  // "XYZ"

Eigen::Matrix3d AxisRotation(Axis axis, double angle_deg);

// R = R(order[2], angles[2]) * R(order[1], angles[1]) * R(order[0], angles[0]): the first
// angle is applied first to a vector (Acclaim "axis ... XYZ" and dof "rx ry rz" mean this).
Eigen::Matrix3d EulerToMatrix(const AxisOrder& order, const Eigen::Vector3d& angles_deg);

// Inverse of EulerToMatrix: angles in degrees, the middle one in [-90, 90]. At gimbal lock
// the first angle is set to zero; the matrix is still reproduced.
Eigen::Vector3d MatrixToEuler(const AxisOrder& order, const Eigen::Matrix3d& rotation);

// Angles (degrees) of `m` about `axes` (0 to 3 distinct axes, applied in that order), as
// for an Acclaim bone whose dofs are fewer than three rotations. Returns the largest
// rotation (degrees) about the remaining axes, which those angles cannot express; 0 when
// `m` is exactly a rotation about `axes`.
double RotationToAngles(const Eigen::Matrix3d& m, std::span<const Axis> axes,
                        std::vector<double>* angles);

// Adds multiples of 360 degrees so that consecutive values differ by at most 180: removes
// the jumps at +/-180 degrees that Euler angle sequences have.
void UnwrapDegrees(std::span<double> angles_deg);

// Wraps into (-180, 180].
double WrapDegrees(double angle_deg);

}  // namespace jgpm
