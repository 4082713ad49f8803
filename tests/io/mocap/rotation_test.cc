#include "io/mocap/rotation.h"

#include <random>

#include <gtest/gtest.h>

namespace jgpm {
namespace {

const AxisOrder kAllOrders[] = {
    {Axis::kX, Axis::kY, Axis::kZ}, {Axis::kX, Axis::kZ, Axis::kY}, {Axis::kY, Axis::kX, Axis::kZ},
    {Axis::kY, Axis::kZ, Axis::kX}, {Axis::kZ, Axis::kX, Axis::kY}, {Axis::kZ, Axis::kY, Axis::kX}};

TEST(Rotation, AxisRotationsTurnAxesByHand) {
  // Right-handed: +90 about z takes x to y, about x takes y to z, about y takes z to x.
  EXPECT_TRUE((AxisRotation(Axis::kZ, 90) * Eigen::Vector3d::UnitX()).isApprox(Eigen::Vector3d::UnitY()));
  EXPECT_TRUE((AxisRotation(Axis::kX, 90) * Eigen::Vector3d::UnitY()).isApprox(Eigen::Vector3d::UnitZ()));
  EXPECT_TRUE((AxisRotation(Axis::kY, 90) * Eigen::Vector3d::UnitZ()).isApprox(Eigen::Vector3d::UnitX()));
}

TEST(Rotation, EulerAppliesTheFirstAxisFirst) {
  // Order XYZ with x = 90 then z = 90: y -> z (x turn) -> z (z turn keeps z).
  const Eigen::Matrix3d r = EulerToMatrix({Axis::kX, Axis::kY, Axis::kZ}, {90, 0, 90});
  EXPECT_TRUE((r * Eigen::Vector3d::UnitY()).isApprox(Eigen::Vector3d::UnitZ(), 1e-12));
  // x -> x (x turn) -> y (z turn).
  EXPECT_TRUE((r * Eigen::Vector3d::UnitX()).isApprox(Eigen::Vector3d::UnitY(), 1e-12));
}

TEST(Rotation, ParseAxisOrder) {
  AxisOrder order;
  ASSERT_TRUE(ParseAxisOrder("zxy", &order));
  EXPECT_EQ(AxisOrderName(order), "ZXY");
  EXPECT_FALSE(ParseAxisOrder("XXY", &order));
  EXPECT_FALSE(ParseAxisOrder("XY", &order));
  EXPECT_FALSE(ParseAxisOrder("XYW", &order));
}

TEST(Rotation, MatrixToEulerInvertsEveryOrder) {
  std::mt19937 random(3);
  std::uniform_real_distribution<double> angle(-180, 180), middle(-89.9, 89.9);
  for (const AxisOrder& order : kAllOrders) {
    for (int i = 0; i < 500; ++i) {
      const Eigen::Vector3d angles(angle(random), middle(random), angle(random));
      const Eigen::Vector3d back = MatrixToEuler(order, EulerToMatrix(order, angles));
      EXPECT_LT((back - angles).cwiseAbs().maxCoeff(), 1e-9) << AxisOrderName(order);
    }
  }
}

TEST(Rotation, MatrixToEulerReproducesTheMatrixAtGimbalLock) {
  for (const AxisOrder& order : kAllOrders) {
    for (double b : {90.0, -90.0}) {
      const Eigen::Matrix3d r = EulerToMatrix(order, {30, b, 40});
      const Eigen::Matrix3d back = EulerToMatrix(order, MatrixToEuler(order, r));
      EXPECT_LT((back - r).cwiseAbs().maxCoeff(), 1e-9) << AxisOrderName(order);
    }
  }
}

TEST(Rotation, RotationToAnglesForFewerDofs) {
  std::vector<double> angles;
  const std::vector<Axis> zx = {Axis::kZ, Axis::kX};
  // z first, then x: R = Rx(b) Rz(a).
  const Eigen::Matrix3d two = AxisRotation(Axis::kX, -25) * AxisRotation(Axis::kZ, 70);
  EXPECT_LT(RotationToAngles(two, zx, &angles), 1e-9);
  ASSERT_EQ(angles.size(), 2u);
  EXPECT_NEAR(angles[0], 70, 1e-9);
  EXPECT_NEAR(angles[1], -25, 1e-9);

  const std::vector<Axis> y = {Axis::kY};
  EXPECT_LT(RotationToAngles(AxisRotation(Axis::kY, 123), y, &angles), 1e-9);
  EXPECT_NEAR(angles[0], 123, 1e-9);
  // A rotation about another axis is reported as the residual.
  EXPECT_NEAR(RotationToAngles(AxisRotation(Axis::kX, 5), y, &angles), 5, 1e-9);
  EXPECT_NEAR(RotationToAngles(AxisRotation(Axis::kZ, 12), {}, &angles), 12, 1e-9);
}

TEST(Rotation, UnwrapRemovesJumps) {
  std::vector<double> a = {170, 179, -179, -170, 175, -185};
  UnwrapDegrees(a);
  EXPECT_EQ(a, (std::vector<double>{170, 179, 181, 190, 175, 175}));
  EXPECT_DOUBLE_EQ(WrapDegrees(190), -170);
  EXPECT_DOUBLE_EQ(WrapDegrees(-180), 180);
  EXPECT_DOUBLE_EQ(WrapDegrees(540), 180);
}

}  // namespace
}  // namespace jgpm
