#include "tracker/body/body_model.h"

#include <algorithm>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include <opencv2/core.hpp>

#include "io/mocap/amc.h"
#include "io/mocap/asf.h"
#include "io/mocap/kinematics.h"
#include "test_support.h"
#include "tracker/body/silhouette.h"

namespace jgpm {
namespace {

TEST(BodyModelTest, PartsFollowTheSkeletonAndHaveHumanSize) {
  const Skeleton skeleton = ReadAsf(test::CmuRoot() / "subjects/07/07.asf");
  const BodyModel body(skeleton, {}, "07.asf");
  EXPECT_EQ(body.NumParts(), 30);
  const Eigen::Matrix3Xd rest = Kinematics(skeleton).Compute(
      std::vector<double>(skeleton.NumChannels(), 0.0).data());
  const std::vector<Capsule> capsules = body.Place(rest);
  ASSERT_EQ(capsules.size(), body.parts().size());
  double top = -1e9, bottom = 1e9, left = 1e9, right = -1e9;
  for (size_t i = 0; i < capsules.size(); ++i) {
    const BodyPart& part = body.parts()[i];
    EXPECT_EQ(capsules[i].from_mm, rest.col(part.from_joint)) << part.name;
    EXPECT_EQ(capsules[i].to_mm, rest.col(part.to_joint)) << part.name;
    for (const auto& [p, r] : {std::pair{capsules[i].from_mm, capsules[i].radius_from_mm},
                               std::pair{capsules[i].to_mm, capsules[i].radius_to_mm}}) {
      top = std::max(top, p.y() + r);
      bottom = std::min(bottom, p.y() - r);
      left = std::min(left, p.x() - r);
      right = std::max(right, p.x() + r);
    }
  }
  // The rest pose stands with arms out: a person's height and arm span (mm).
  std::printf("rest pose: height %.0f mm, span %.0f mm\n", top - bottom, right - left);
  EXPECT_GT(top - bottom, 1500);
  EXPECT_LT(top - bottom, 2000);
  EXPECT_GT(right - left, 1400);
  EXPECT_LT(right - left, 2000);
  // The femur part runs hip -> knee.
  const int femur = skeleton.FindBone("lfemur");
  const auto it = std::find_if(body.parts().begin(), body.parts().end(),
                               [](const BodyPart& p) { return p.name == "lfemur"; });
  ASSERT_NE(it, body.parts().end());
  EXPECT_EQ(it->to_joint, femur);
  EXPECT_EQ(it->from_joint, skeleton.bones[femur].parent);
}

// The tracker's coarser body (BodyDetail::kTracking) differs from the full one only at the
// hands and the neck: drawn through cameras that see the walker 130 px tall, from the side
// and from the front, every 10th frame of a walk, the pixels the two disagree on are a
// fraction of what the full body's hand and neck parts cover on their own.
TEST(BodyModelTest, TheTrackingBodyDiffersOnlyAtTheHandsAndNeck) {
  const Skeleton skeleton = ReadAsf(test::CmuRoot() / "subjects/07/07.asf");
  const Motion motion = ReadAmc(test::CmuRoot() / "subjects/07/07_01.amc", skeleton);
  const BodyModel full(skeleton, {}, "07.asf");
  const BodyModel tracking(skeleton, {.detail = BodyDetail::kTracking}, "07.asf");
  ASSERT_EQ(tracking.NumParts(), 25);
  const auto wrist = std::find_if(tracking.parts().begin(), tracking.parts().end(),
                                  [](const BodyPart& p) { return p.name == "lwrist"; });
  ASSERT_NE(wrist, tracking.parts().end());
  EXPECT_EQ(wrist->to_joint, skeleton.FindBone("lfingers"));
  const std::vector<std::string> small = {"lwrist",   "rwrist",   "lhand",     "rhand",
                                          "lfingers", "rfingers", "lowerneck", "upperneck"};
  const std::vector<Eigen::Matrix3Xd> joints = ComputeJointPositions(skeleton, motion);
  double differ = 0, small_area = 0, area = 0;
  for (size_t f = 0; f < joints.size(); f += 10) {
    const Eigen::Vector3d root = joints[f].col(0);
    for (const Eigen::Vector3d& eye : {Eigen::Vector3d(4000, 0, 0), Eigen::Vector3d(0, 0, 4000)}) {
      const Camera camera = LookAtCamera("c", 320, 240, 300, root + eye + Eigen::Vector3d(0, 200, 0), root);
      const SilhouetteRenderer renderer(camera);
      const std::vector<Capsule> full_body = full.Place(joints[f]);
      std::vector<Capsule> small_parts;
      for (int i = 0; i < full.NumParts(); ++i) {
        if (std::find(small.begin(), small.end(), full.parts()[i].name) != small.end()) small_parts.push_back(full_body[i]);
      }
      cv::Mat a, b, s;
      renderer.Render(full_body, &a);
      renderer.Render(tracking.Place(joints[f]), &b);
      renderer.Render(small_parts, &s);
      differ += cv::countNonZero(a != b);
      small_area += cv::countNonZero(s);
      area += cv::countNonZero(a);
    }
  }
  std::printf("over every view: the full body %.0f px, its hands and neck %.0f, the two bodies differ on %.0f\n", area,
              small_area, differ);
  EXPECT_GT(small_area, 0.03 * area);
  EXPECT_LT(differ, 0.3 * small_area);
}

TEST(BodyModelTest, WidthScaleScalesEveryRadius) {
  const Skeleton skeleton = ReadAsf(test::CmuRoot() / "subjects/35/35.asf");
  const BodyModel normal(skeleton, {}, "35.asf");
  BodyModelOptions options;
  options.width_scale = 1.2;
  const BodyModel broad(skeleton, options, "35.asf");
  for (int i = 0; i < normal.NumParts(); ++i) {
    EXPECT_DOUBLE_EQ(broad.parts()[i].radius_from_mm, 1.2 * normal.parts()[i].radius_from_mm);
    EXPECT_DOUBLE_EQ(broad.parts()[i].radius_to_mm, 1.2 * normal.parts()[i].radius_to_mm);
  }
}

TEST(BodyModelTest, RegionScalesScaleTheirRegionsPartsOnly) {
  const Skeleton skeleton = ReadAsf(test::CmuRoot() / "subjects/35/35.asf");
  BodyModelOptions options;
  options.width_scale = 1.1;
  const BodyModel normal(skeleton, options, "35.asf");
  BodyModel shaped(skeleton, options, "35.asf");
  const RegionScales shape = {1.2, 0.9, 1.0, 1.3, 0.8};
  shaped.SetRegionScales(shape);
  EXPECT_EQ(shaped.region_scales(), shape);
  int thighs = 0;
  for (int i = 0; i < normal.NumParts(); ++i) {
    const BodyPart& part = shaped.parts()[i];
    const double expected = shape[static_cast<int>(part.region)];
    // By name, not by the region table: a thigh is 1.3 wider, a shin 0.8, the rest as set.
    if (part.name == "lfemur" || part.name == "rfemur") {
      EXPECT_EQ(part.region, BodyRegion::kThighs);
      ++thighs;
    }
    if (part.name == "ltibia" || part.name == "lfoot") { EXPECT_EQ(part.region, BodyRegion::kShins); }
    if (part.name == "head") { EXPECT_EQ(part.region, BodyRegion::kHead); }
    if (part.name == "rhand") { EXPECT_EQ(part.region, BodyRegion::kArms); }
    if (part.name == "chest") { EXPECT_EQ(part.region, BodyRegion::kTorso); }
    EXPECT_DOUBLE_EQ(part.radius_from_mm, expected * normal.parts()[i].radius_from_mm) << part.name;
    EXPECT_DOUBLE_EQ(part.radius_to_mm, expected * normal.parts()[i].radius_to_mm) << part.name;
  }
  EXPECT_EQ(thighs, 2);
  // Placing with a shape and a scale equals setting the shape and scaling the radii.
  const Eigen::Matrix3Xd rest = Kinematics(skeleton).Compute(std::vector<double>(skeleton.NumChannels(), 0.0).data());
  std::vector<Capsule> direct;
  normal.Place(rest, 1.5, shape, 0, &direct);
  const std::vector<Capsule> set = shaped.Place(rest);
  for (size_t i = 0; i < set.size(); ++i) {
    EXPECT_DOUBLE_EQ(direct[i].radius_from_mm, 1.5 * set[i].radius_from_mm);
    EXPECT_DOUBLE_EQ(direct[i].radius_to_mm, 1.5 * set[i].radius_to_mm);
    EXPECT_EQ(direct[i].from_mm, set[i].from_mm);
  }
  EXPECT_EQ(BodyRegionName(BodyRegion::kThighs), "thighs");
}

// The garment, by hand: a cone from the hips' centre kGarmentLength of the way to the
// knees' centre, radii times the garment, the width scale and the placing scale; none at 0.
TEST(BodyModelTest, TheGarmentHangsFromTheHipsTowardsTheKnees) {
  const Skeleton skeleton = ReadAsf(test::CmuRoot() / "subjects/07/07.asf");
  BodyModelOptions broad;
  broad.width_scale = 1.2;
  BodyModel body(skeleton, broad, "07.asf");
  const std::vector<double> pose(skeleton.NumChannels(), 0.0);
  const Eigen::Matrix3Xd rest = Kinematics(skeleton).Compute(pose.data());
  EXPECT_EQ(body.Place(rest).size(), static_cast<size_t>(body.NumParts()));
  body.SetGarment(0.8);
  const std::vector<Capsule> dressed = body.Place(rest);
  ASSERT_EQ(dressed.size(), static_cast<size_t>(body.NumParts()) + 1);
  const Eigen::Vector3d hips = 0.5 * (rest.col(skeleton.FindBone("lhipjoint")) + rest.col(skeleton.FindBone("rhipjoint")));
  const Eigen::Vector3d knees = 0.5 * (rest.col(skeleton.FindBone("lfemur")) + rest.col(skeleton.FindBone("rfemur")));
  const Capsule& garment = dressed.back();
  EXPECT_LT((garment.from_mm - hips).norm(), 1e-9);
  EXPECT_LT((garment.to_mm - (hips + 0.75 * (knees - hips))).norm(), 1e-9);
  EXPECT_DOUBLE_EQ(garment.radius_from_mm, 150 * 0.8 * 1.2);
  EXPECT_DOUBLE_EQ(garment.radius_to_mm, 200 * 0.8 * 1.2);
  // Placed with an explicit build: its own garment, times the placing scale.
  std::vector<Capsule> placed;
  body.Place(rest, 1.5, kUnitRegionScales, 0.5, &placed);
  ASSERT_EQ(placed.size(), dressed.size());
  EXPECT_DOUBLE_EQ(placed.back().radius_to_mm, 200 * 0.5 * 1.2 * 1.5);
  body.Place(rest, 1.5, kUnitRegionScales, 0, &placed);
  EXPECT_EQ(placed.size(), static_cast<size_t>(body.NumParts()));
}

TEST(BodyModelTest, BadInputIsNamed) {
  Skeleton skeleton = ReadAsf(test::CmuRoot() / "subjects/35/35.asf");
  BodyModelOptions options;
  options.width_scale = 0;
  test::ExpectInputError([&] { BodyModel(skeleton, options, "35.asf"); }, {"35.asf", "width scale"});
  skeleton.bones[skeleton.FindBone("ltibia")].name = "lshin";
  test::ExpectInputError([&] { BodyModel(skeleton, {}, "odd.asf"); }, {"odd.asf", "'ltibia'"});
}

}  // namespace
}  // namespace jgpm
