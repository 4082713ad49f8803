// Latent transition paths (prior/motion/latent_transition.h) against their definition: the three
// constraints of eqs. 19-21 measured on every generated point (to 1e-9), each point's angle
// against a brute-force search of its allowed arc (the oracle for "solved exactly"), the
// straight line as LSOPA with l = 0, and the baselines' own definitions.
#include "prior/motion/latent_transition.h"

#include <cmath>
#include <numbers>
#include <random>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "test_support.h"

namespace jgpm {
namespace {

using test::ExpectInputError;


// A smooth, non-convex map from latent points to 5-D "poses".
Eigen::MatrixXd Wavy(const Eigen::MatrixXd& xs) {
  Eigen::MatrixXd poses(xs.rows(), 5);
  for (Eigen::Index k = 0; k < xs.rows(); ++k) {
    const double x = xs(k, 0), y = xs(k, 1), z = xs(k, 2);
    poses.row(k) << std::sin(2 * x) + y, std::cos(3 * y) * z, x * y - z, std::sin(x + 2 * z), 0.5 * z * z;
  }
  return poses;
}

Eigen::MatrixXd Identity(const Eigen::MatrixXd& xs) { return xs; }

struct Case {
  Eigen::Vector3d a, b, c;
};

std::vector<Case> RandomCases(int count) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-2, 2);
  std::vector<Case> cases;
  while (static_cast<int>(cases.size()) < count) {
    const Eigen::Vector3d a(u(rng), u(rng), u(rng)), b(u(rng), u(rng), u(rng)), c(u(rng), u(rng), u(rng));
    if ((b - a).norm() > 0.5) cases.push_back({a, b, c});
  }
  return cases;
}

// Angle (radians) of the point's offset from the line a-b, measured from C about d.
double OffsetAngle(const Eigen::Vector3d& x, const Case& k) {
  const Eigen::Vector3d d = k.b - k.a, unit_d = d.normalized();
  const Eigen::Vector3d v = x - k.a, r = v - v.dot(unit_d) * unit_d;
  const Eigen::Vector3d c = (k.c - k.c.dot(unit_d) * unit_d).normalized();
  return std::atan2(unit_d.cross(c).dot(r), c.dot(r));
}

TEST(LatentTransition, EveryPointMeetsTheThreeConstraints) {
  LatentTransitionOptions options;
  for (const int frames : {5, 15, 30}) {
    options.frames = frames;
    for (const Case& k : RandomCases(10)) {
      const Eigen::MatrixXd path = LsopaPath(k.a, k.b, k.c, options, Wavy);
      ASSERT_EQ(path.rows(), frames);
      const Eigen::Vector3d d = k.b - k.a;
      for (int i = 1; i <= frames; ++i) {
        const Eigen::Vector3d v = path.row(i - 1).transpose() - k.a;
        const double progress = v.dot(d) / d.squaredNorm();
        const Eigen::Vector3d r = v - progress * d;
        const double l = options.peak_offset * (frames + 1) * std::sin(std::numbers::pi * i / (frames + 1));
        EXPECT_NEAR(progress, static_cast<double>(i) / (frames + 1), 1e-9);      // eq. 19
        EXPECT_NEAR(r.norm(), l * d.norm() / (frames + 1), 1e-9);                // eq. 20
        EXPECT_LE(std::abs(OffsetAngle(path.row(i - 1).transpose(), k)),         // eq. 21
                  options.max_angle_deg * std::numbers::pi / 180 + 1e-9);
      }
    }
  }
}

// Each point is the best on its allowed arc given the point before: brute force over
// 200,001 angles finds no better step (the oracle), and the angle found is that one.
TEST(LatentTransition, EachPointIsTheArcsBest) {
  LatentTransitionOptions options;
  options.frames = 9;
  options.peak_offset = 0.25;  // a wide arc, so that the best is often inside it
  options.max_angle_deg = 60;
  const double theta = options.max_angle_deg * std::numbers::pi / 180;
  for (const Case& k : RandomCases(6)) {
    const Eigen::MatrixXd path = LsopaPath(k.a, k.b, k.c, options, Wavy);
    const Eigen::Vector3d d = k.b - k.a, unit_d = d.normalized();
    const Eigen::Vector3d u = (k.c - k.c.dot(unit_d) * unit_d).normalized(), w = unit_d.cross(u);
    Eigen::Vector3d previous = k.a;
    for (int i = 1; i <= options.frames; ++i) {
      const double t = static_cast<double>(i) / (options.frames + 1);
      const double radius = options.peak_offset * d.norm() * std::sin(std::numbers::pi * t);
      const int n = 200001;
      Eigen::MatrixXd xs(n, 3);
      for (int s = 0; s < n; ++s) {
        const double phi = -theta + 2 * theta * s / (n - 1);
        xs.row(s) = (k.a + t * d + radius * (std::cos(phi) * u + std::sin(phi) * w)).transpose();
      }
      const Eigen::VectorXd steps = (Wavy(xs).rowwise() - Wavy(previous.transpose()).row(0)).rowwise().norm();
      Eigen::Index best;
      const double brute = steps.minCoeff(&best);
      const Eigen::Vector3d x = path.row(i - 1).transpose();
      const double found = (Wavy(x.transpose()) - Wavy(previous.transpose())).norm();
      EXPECT_LE(found, brute + 1e-9) << "point " << i;
      EXPECT_NEAR(OffsetAngle(x, k), -theta + 2 * theta * best / (n - 1), 2e-4) << "point " << i;
      previous = x;
    }
  }
}

// A case solved by hand: d along x, C = +y, so the arc is (t, r cos phi, r sin phi), and with
// f(x) = x_y - x_z the first step |r (cos phi - sin phi)| is smallest at phi = 45 degrees.
// With theta = 30 the bound holds the first point at +30 degrees exactly.
TEST(LatentTransition, TheAngleBoundHoldsWhenTheBestLiesBeyondIt) {
  const Case k{Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(0, 1, 0)};
  LatentTransitionOptions options;
  options.frames = 3;
  options.max_angle_deg = 30;
  const Eigen::MatrixXd path = LsopaPath(k.a, k.b, k.c, options, [](const Eigen::MatrixXd& xs) {
    return Eigen::MatrixXd(xs.col(1) - xs.col(2));
  });
  EXPECT_NEAR(OffsetAngle(path.row(0).transpose(), k), 30 * std::numbers::pi / 180, 1e-9);
  options.max_angle_deg = 60;  // now within reach: 45 degrees
  const Eigen::MatrixXd free = LsopaPath(k.a, k.b, k.c, options, [](const Eigen::MatrixXd& xs) {
    return Eigen::MatrixXd(xs.col(1) - xs.col(2));
  });
  EXPECT_NEAR(OffsetAngle(free.row(0).transpose(), k), 45 * std::numbers::pi / 180, 1e-6);
}

TEST(LatentTransition, TheLineIsLsopaWithoutOffset) {
  LatentTransitionOptions options;
  options.peak_offset = 0;
  for (const int frames : {1, 5, 15}) {
    options.frames = frames;
    for (const Case& k : RandomCases(5)) {
      const Eigen::MatrixXd lsopa = LsopaPath(k.a, k.b, k.c, options, Wavy);
      const Eigen::MatrixXd line = LinearPath(k.a, k.b, frames);
      EXPECT_LT((lsopa - line).cwiseAbs().maxCoeff(), 1e-12);
      for (int i = 1; i <= frames; ++i) {  // evenly spaced, on the segment
        const Eigen::Vector3d expected = k.a + (static_cast<double>(i) / (frames + 1)) * (k.b - k.a);
        EXPECT_LT((line.row(i - 1).transpose() - expected).norm(), 1e-12);
      }
    }
  }
}

TEST(LatentTransition, RandomPointsLieInTheBoxInOrderAlongD) {
  const Eigen::Vector3d a(-1, 2, 0.5), b(1.5, -1, 2);
  const Eigen::Vector3d lo = a.cwiseMin(b), hi = a.cwiseMax(b);
  for (uint64_t seed = 1; seed <= 20; ++seed) {
    const Eigen::MatrixXd path = RandomPath(a, b, 15, seed);
    ASSERT_EQ(path.rows(), 15);
    double last = -1e300;
    for (int i = 0; i < 15; ++i) {
      const Eigen::Vector3d x = path.row(i).transpose();
      EXPECT_TRUE((x.array() >= lo.array()).all() && (x.array() <= hi.array()).all());
      const double progress = (x - a).dot(b - a);
      EXPECT_GE(progress, last);
      last = progress;
    }
    EXPECT_EQ(path, RandomPath(a, b, 15, seed));                // the same seed, the same points
    EXPECT_GT((path - RandomPath(a, b, 15, seed + 1)).norm(), 0.1);  // another seed, others
  }
}

TEST(LatentTransition, ReferenceIsAsLastVelocityOrthogonalToD) {
  const Eigen::Vector3d a(0, 0, 0), b(2, 0, 0);
  // A moved along +x and +y: C is +y.
  EXPECT_LT((ReferenceDirection(Eigen::Vector3d(-1, -0.5, 0), a, b, Eigen::Vector3d(3, 0, 0)) -
             Eigen::Vector3d(0, 1, 0)).norm(), 1e-12);
  // A moved along d: B's first velocity's orthogonal part (+z) is taken.
  EXPECT_LT((ReferenceDirection(Eigen::Vector3d(-1, 0, 0), a, b, Eigen::Vector3d(3, 0, 0.2)) -
             Eigen::Vector3d(0, 0, 1)).norm(), 1e-12);
  // Both along d: a unit vector orthogonal to d.
  const Eigen::Vector3d c = ReferenceDirection(Eigen::Vector3d(-1, 0, 0), a, b, Eigen::Vector3d(3, 0, 0));
  EXPECT_NEAR(c.norm(), 1, 1e-12);
  EXPECT_NEAR(c.dot(b - a), 0, 1e-12);
}

TEST(LatentTransition, RefusesBadInput) {
  const Eigen::Vector3d a(0, 0, 0), b(1, 1, 0), c(0, 0, 1);
  const LatentTransitionOptions ok;
  ExpectInputError([&] { LsopaPath(a, a, c, ok, Identity); }, {"coincide"});
  ExpectInputError([&] { LsopaPath(a, b, b - a, ok, Identity); }, {"parallel"});
  ExpectInputError([&] { LsopaPath(Eigen::Vector3d(NAN, 0, 0), b, c, ok, Identity); }, {"not finite"});
  ExpectInputError([&] { LsopaPath(a, b, c, ok, [](const Eigen::MatrixXd& xs) {
                       return Eigen::MatrixXd(Eigen::MatrixXd::Constant(xs.rows(), 2, NAN));
                     }); }, {"non-finite"});
  ExpectInputError([&] { LsopaPath(a, b, c, ok, [](const Eigen::MatrixXd&) { return Eigen::MatrixXd(1, 2); }); }, {"returned"});
  LatentTransitionOptions bad;
  bad.frames = 0;
  ExpectInputError([&] { LsopaPath(a, b, c, bad, Identity); }, {"frames"});
  bad = ok;
  bad.max_angle_deg = 190;
  ExpectInputError([&] { LsopaPath(a, b, c, bad, Identity); }, {"max_angle_deg"});
  bad = ok;
  bad.peak_offset = -1;
  ExpectInputError([&] { LsopaPath(a, b, c, bad, Identity); }, {"peak_offset"});
  ExpectInputError([&] { LinearPath(a, b, 0); }, {"frames"});
  ExpectInputError([&] { RandomPath(a, a, 5, 1); }, {"coincide"});
}

}  // namespace
}  // namespace jgpm
