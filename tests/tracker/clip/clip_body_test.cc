// The rendered person: without options exactly the tracker's body; a body seed another
// person of the same bones; clothing and a bag volumes the tracker's capsules do not have,
// which the ray caster draws where they are.
#include "tracker/clip/clip_body.h"

#include <gtest/gtest.h>
#include <opencv2/core.hpp>

#include "io/mocap/amc.h"
#include "io/mocap/asf.h"
#include "io/mocap/kinematics.h"
#include "tracker/body/ray_caster.h"
#include "test_support.h"

namespace jgpm {
namespace {

struct Pose {
  Skeleton skeleton;
  Eigen::Matrix3Xd joints;
};
const Pose& Walker() {
  static const Pose pose = [] {
    Pose p;
    p.skeleton = ReadAsf(test::CmuRoot() / "subjects/07/07.asf");
    const Motion motion = ReadAmc(test::CmuRoot() / "subjects/07/07_01.amc", p.skeleton);
    Kinematics(p.skeleton).Compute(motion.Frame(60), &p.joints);
    return p;
  }();
  return pose;
}

// A camera 4 m to the walker's side, looking at his middle.
Camera SideCamera(const Eigen::Matrix3Xd& joints) {
  const Eigen::Vector3d root = joints.col(0);
  return LookAtCamera("cam0", 320, 240, 300, root + Eigen::Vector3d(4000, 0, 0), root);
}

cv::Mat Mask(const ClipBody& body, const Eigen::Matrix3Xd& joints) {
  std::vector<Capsule> capsules;
  body.Place(joints, &capsules);
  BodyImage image;
  RayCaster(SideCamera(joints)).Render(capsules, &image);
  return image.Mask();
}

TEST(ClipBody, WithoutOptionsIsTheTrackersBody) {
  const Pose& p = Walker();
  for (double width : {1.0, 1.2}) {
    BodyModelOptions tracker_options;
    tracker_options.width_scale = width;
    ClipBodyOptions options;
    options.width_scale = width;
    ASSERT_TRUE(options.TrackersBody());
    const std::vector<Capsule> expected = BodyModel(p.skeleton, tracker_options, "s").Place(p.joints);
    std::vector<Capsule> got;
    ClipBody(p.skeleton, options, "s").Place(p.joints, &got);
    ASSERT_EQ(got.size(), expected.size());
    for (size_t i = 0; i < got.size(); ++i) {
      EXPECT_EQ(got[i].from_mm, expected[i].from_mm) << i;
      EXPECT_EQ(got[i].to_mm, expected[i].to_mm) << i;
      EXPECT_EQ(got[i].radius_from_mm, expected[i].radius_from_mm) << i;  // exactly: today's clips
      EXPECT_EQ(got[i].radius_to_mm, expected[i].radius_to_mm) << i;
    }
  }
}

TEST(ClipBody, ASeedIsAnotherPersonOnTheSameBones) {
  const Pose& p = Walker();
  const std::vector<Capsule> mean = BodyModel(p.skeleton, {}, "s").Place(p.joints);
  std::vector<double> overall;
  for (uint64_t seed = 1; seed <= 40; ++seed) {
    ClipBodyOptions options;
    options.body_seed = seed;
    std::vector<Capsule> a, b;
    ClipBody(p.skeleton, options, "s").Place(p.joints, &a);
    ClipBody(p.skeleton, options, "s").Place(p.joints, &b);
    ASSERT_EQ(a.size(), mean.size());
    double ratio_sum = 0;
    for (size_t i = 0; i < a.size(); ++i) {
      EXPECT_EQ(a[i].from_mm, mean[i].from_mm);  // bone lengths stay the subject's
      EXPECT_EQ(a[i].to_mm, mean[i].to_mm);
      EXPECT_EQ(a[i].radius_from_mm, b[i].radius_from_mm);  // one person per seed
      const double ratio = a[i].radius_from_mm / mean[i].radius_from_mm;
      // Overall +-2 sd of 12% times a region's +-2 sd of at most 8%.
      EXPECT_GT(ratio, 0.76 * 0.84) << seed << " " << i;
      EXPECT_LT(ratio, 1.24 * 1.16) << seed << " " << i;
      ratio_sum += ratio;
    }
    overall.push_back(ratio_sum / a.size());
  }
  // Thin to heavy: the people differ, around the adult mean.
  const auto [thin, heavy] = std::minmax_element(overall.begin(), overall.end());
  EXPECT_LT(*thin, 0.92);
  EXPECT_GT(*heavy, 1.08);
  double sum = 0;
  for (double r : overall) sum += r;
  EXPECT_NEAR(sum / overall.size(), 1.0, 0.06);
}

TEST(ClipBody, ClothingAndABagAddVolumeTheTrackersBodyLacks) {
  const Pose& p = Walker();
  const cv::Mat plain = Mask(ClipBody(p.skeleton, {}, "s"), p.joints);
  const int plain_px = cv::countNonZero(plain);
  ASSERT_GT(plain_px, 1000);
  for (Clothing clothing : {Clothing::kTrousers, Clothing::kCoat, Clothing::kSkirt}) {
    SCOPED_TRACE(std::string(ClothingName(clothing)));
    ClipBodyOptions options;
    options.clothing = clothing;
    const cv::Mat dressed = Mask(ClipBody(p.skeleton, options, "s"), p.joints);
    // Clothes only add: every pixel of the body stays covered, and more is.
    EXPECT_EQ(cv::countNonZero(plain & ~dressed), 0);
    EXPECT_GT(cv::countNonZero(dressed), plain_px * 1.04);
  }
  ClipBodyOptions bag;
  bag.bag = true;
  const ClipBody with_bag(p.skeleton, bag, "s");
  EXPECT_EQ(with_bag.shapes().back().name, "strap");
  EXPECT_EQ(cv::countNonZero(plain & ~Mask(with_bag, p.joints)), 0);
  // The bag hangs beside the right hip: between the hips' heights and 0.35 m below them,
  // farther right of the body's centre than the right hip joint.
  std::vector<Capsule> capsules;
  with_bag.Place(p.joints, &capsules);
  const Capsule& b = capsules[capsules.size() - 2];
  const Eigen::Vector3d l = p.joints.col(p.skeleton.FindBone("lhipjoint")), r = p.joints.col(p.skeleton.FindBone("rhipjoint"));
  const Eigen::Vector3d middle = 0.5 * (l + r), right = (r - l).normalized();
  EXPECT_GT((b.from_mm - middle).dot(right), (r - middle).dot(right) + 100);
  EXPECT_LT(b.to_mm.y(), middle.y());
}

TEST(ClipBody, NamesParseBackAndBadOptionsAreRefused) {
  for (Clothing c : {Clothing::kNone, Clothing::kTrousers, Clothing::kCoat, Clothing::kSkirt}) {
    Clothing back = Clothing::kNone;
    EXPECT_TRUE(ParseClothing(ClothingName(c), &back));
    EXPECT_EQ(back, c);
  }
  Clothing unchanged = Clothing::kCoat;
  EXPECT_FALSE(ParseClothing("cape", &unchanged));
  EXPECT_EQ(unchanged, Clothing::kCoat);
  ClipBodyOptions bad;
  bad.width_scale = 0;
  test::ExpectInputError([&] { ClipBody(Walker().skeleton, bad, "the.asf"); }, {"the.asf", "width scale"});
}

}  // namespace
}  // namespace jgpm
