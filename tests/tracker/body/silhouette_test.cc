// The fast silhouette against a hand computation (one bar seen face on) and against the
// exact ray caster (whole bodies from real motion, with and without lens distortion).
#include "tracker/body/silhouette.h"

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "io/mocap/amc.h"
#include "io/mocap/asf.h"
#include "io/mocap/kinematics.h"
#include "test_support.h"
#include "tracker/body/bit_silhouette.h"
#include "tracker/body/ray_caster.h"

namespace jgpm {
namespace {

double IoU(const cv::Mat& a, const cv::Mat& b) {
  return static_cast<double>(cv::countNonZero(a & b)) / cv::countNonZero(a | b);
}

TEST(SilhouetteTest, BarSeenFaceOnMatchesHandComputation) {
  // A horizontal bar 840 mm long, radius 58 mm, 4 m in front of a 320x240 camera, f=300:
  // an image stadium of half-length 420 * 300/4000 = 31.5 px and radius 4.35 px about
  // (159.5, 119.5), so pixel centres u in [123.65, 195.35], v in [115.15, 123.85].
  const Camera camera = LookAtCamera("c", 320, 240, 300, {0, 1000, -4000}, {0, 1000, 0});
  const SilhouetteRenderer renderer(camera);
  const Capsule bar{{-420, 1000, 0}, {420, 1000, 0}, 58, 58};
  cv::Mat mask;
  const cv::Rect drawn = renderer.Render({bar}, &mask);
  const double half = 31.5, r = 4.35;
  // The pixel centres inside it (its area is 607.5 px^2, but only 8 rows of centres fit
  // in its 8.7 px height):
  int inside = 0;
  for (int v = 0; v < 240; ++v)
    for (int u = 0; u < 320; ++u) {
      const double du = std::max(0.0, std::abs(u - 159.5) - half), dv = v - 119.5;
      inside += du * du + dv * dv <= r * r;
    }
  EXPECT_EQ(inside, 564);
  EXPECT_NEAR(cv::countNonZero(mask), inside, 0.03 * inside);
  const cv::Rect box = cv::boundingRect(mask);
  EXPECT_EQ(box.x, 124);
  EXPECT_EQ(box.x + box.width - 1, 195);
  EXPECT_EQ(box.y, 116);
  EXPECT_EQ(box.y + box.height - 1, 123);
  EXPECT_EQ(drawn & box, box);  // the reported box holds everything drawn
  // The exact image agrees.
  const RayCaster caster(camera);
  BodyImage exact;
  caster.Render({bar}, &exact);
  EXPECT_NEAR(cv::countNonZero(exact.Mask()), inside, 0.01 * inside);
  EXPECT_GT(IoU(mask, exact.Mask()), 0.95);
}

TEST(SilhouetteTest, TaperedPartAndPartsBehindTheCamera) {
  const Camera camera = LookAtCamera("c", 320, 240, 300, {0, 0, -3000}, {0, 0, 0});
  const SilhouetteRenderer renderer(camera);
  const RayCaster caster(camera);
  // A cone-like limb pointing partly at the camera, and one behind it (skipped, no crash).
  const std::vector<Capsule> parts = {{{-300, -200, 300}, {300, 250, -600}, 120, 40},
                                      {{0, 0, -3500}, {0, 100, -3200}, 50, 50}};
  cv::Mat mask;
  renderer.Render(parts, &mask);
  BodyImage exact;
  caster.Render(parts, &exact);
  EXPECT_GT(IoU(mask, exact.Mask()), 0.95);
  // One end holding the other: a sphere.
  renderer.Render({{{0, 0, 0}, {0, 0, 10}, 200, 50}}, &mask);
  caster.Render({{{0, 0, 0}, {0, 0, 10}, 200, 50}}, &exact);
  EXPECT_GT(IoU(mask, exact.Mask()), 0.95);
}

// Particles wander off: a part beyond the lens's monotone range must not be folded back
// into the image, parts far outside it or at absurd distances must not overflow the
// fixed-point polygon coordinates (undefined behaviour), and nothing may be drawn for them.
TEST(SilhouetteTest, OffAxisAndNearCameraPartsAreCulledNotFolded) {
  Camera camera = LookAtCamera("c", 320, 240, 300, {0, 1000, -3000}, {0, 1000, 0});
  camera.distortion = {-0.5, 0, 0, 0, 0};  // r (1 - 0.5 r^2) grows only up to r = 0.816
  const SilhouetteRenderer renderer(camera);
  EXPECT_NEAR(renderer.max_normalised_radius(), std::sqrt(2.0 / 3), 2e-3);
  // A limb at normalised radius 1.2 (50 degrees off axis): the polynomial would put it at
  // r_d = 0.336, 100 px from the centre, well inside the image.
  const double z = 3000, x = 1.2 * z;
  Eigen::Vector2d folded;
  ASSERT_TRUE(camera.Project({x, 1000, 0}, &folded));
  ASSERT_LT(std::abs(folded.x() - 159.5), 120);  // the fold is real...
  cv::Mat mask;
  EXPECT_TRUE(renderer.Render({{{x, 1000, 0}, {x + 100, 1000, 0}, 60, 60}}, &mask).empty());
  EXPECT_EQ(cv::countNonZero(mask), 0);  // ...and nothing is drawn for it
  // Just in front of the camera, behind it, at absurd coordinates, NaN: nothing drawn.
  const Eigen::Vector3d eye = camera.CentreInWorld();
  const std::vector<Capsule> wild = {
      {eye + Eigen::Vector3d(0, 0, 50), eye + Eigen::Vector3d(0, 100, 50), 40, 40},
      {eye + Eigen::Vector3d(0, 0, -500), eye + Eigen::Vector3d(0, 0, 500), 40, 40},
      {eye + Eigen::Vector3d(1e12, 0, 100.5), eye + Eigen::Vector3d(-1e12, 0, 100.5), 1e9, 1e9},
      {{std::nan(""), 0, 0}, {0, 0, 0}, 40, 40},
  };
  mask.setTo(0);
  EXPECT_TRUE(renderer.Draw(wild, &mask).empty());
  EXPECT_EQ(cv::countNonZero(mask), 0);
  // A part reaching far off the image but in the lens's range is still drawn where it is.
  const Camera pinhole = LookAtCamera("p", 320, 240, 300, {0, 1000, -3000}, {0, 1000, 0});
  const cv::Rect drawn = SilhouetteRenderer(pinhole).Render({{{0, 1000, 0}, {2500, 1000, 0}, 60, 60}}, &mask);
  EXPECT_GT(cv::countNonZero(mask), 150 * 10);  // half the image's width, 12 px thick
  EXPECT_TRUE(drawn.x == 0 || drawn.br().x == 320) << "reaches the border";
}

struct Walk {
  Skeleton skeleton;
  Motion motion;
};
const Walk& RealWalk() {
  static const Walk walk = [] {
    Walk w;
    w.skeleton = ReadAsf(test::CmuRoot() / "subjects/35/35.asf");
    w.motion = ReadAmc(test::CmuRoot() / "subjects/35/35_01.amc", w.skeleton);
    return w;
  }();
  return walk;
}

// A wide webcam sees a part 40 degrees off its axis as an ellipse 1 / cos(40) = 1.31
// times longer along the line from the image centre than across it; a circle of radius
// f r / z (the renderers' shape before) covers only 76% of it. Both renderers against the
// exact ray caster, for a lone sphere and for a limb.
TEST(SilhouetteTest, PartsOffTheAxisOfAWideCameraAreEllipses) {
  const Camera camera = LookAtCamera("webcam", 640, 480, 320, {0, 1500, -3000}, {0, 1500, 0});  // 90 degrees wide
  const double angle = 40 * std::numbers::pi / 180;
  const Eigen::Vector3d centre = camera.CentreInWorld() + 3000 * Eigen::Vector3d(std::sin(angle), 0, std::cos(angle));
  for (const Eigen::Vector3d& along : {Eigen::Vector3d(0, 0.1, 0), Eigen::Vector3d(0, 350, 0)}) {
    const std::vector<Capsule> part{{centre - along, centre + along, 120, 120}};
    cv::Mat fast;
    SilhouetteRenderer(camera).Render(part, &fast);
    BodyImage exact;
    RayCaster(camera).Render(part, &exact);
    const int exact_px = cv::countNonZero(exact.Mask());
    EXPECT_NEAR(cv::countNonZero(fast), exact_px, 0.03 * exact_px);
    EXPECT_GT(IoU(fast, exact.Mask()), 0.95);
    BitMask bits(camera.width, camera.height);
    BitSilhouetteRenderer(camera).Draw(part, &bits);
    EXPECT_NEAR(bits.Count(), exact_px, 0.03 * exact_px);
    EXPECT_GT(IoU(bits.ToMat(), exact.Mask()), 0.95);
  }
}

TEST(SilhouetteTest, RealWalkAgreesWithExactRenderingAndCoversTheJoints) {
  const Walk& walk = RealWalk();
  const BodyModel body(walk.skeleton, {}, "35.asf");
  const Kinematics kinematics(walk.skeleton);
  double worst_iou = 1, mean_iou = 0;
  int images = 0;
  for (int distorted = 0; distorted < 2; ++distorted) {
    for (int frame = 0; frame < walk.motion.NumFrames(); frame += 60) {
      const Eigen::Matrix3Xd joints = kinematics.Compute(walk.motion.Frame(frame));
      const Eigen::Vector3d root = joints.col(0);
      for (double azimuth : {0.0, 1.2, 2.5}) {
        const Eigen::Vector3d centre(root.x() + 4500 * std::sin(azimuth), 1500,
                                     root.z() + 4500 * std::cos(azimuth));
        Camera camera = LookAtCamera("c", 320, 240, 280, centre, {root.x(), 900, root.z()});
        if (distorted) camera.distortion = {-0.25, 0.08, 0.001, 0.001, 0};
        cv::Mat mask;
        const std::vector<Capsule> capsules = body.Place(joints);
        const cv::Rect drawn = SilhouetteRenderer(camera).Render(capsules, &mask);
        BodyImage exact;
        RayCaster(camera).Render(capsules, &exact);
        const double iou = IoU(mask, exact.Mask());
        worst_iou = std::min(worst_iou, iou);
        mean_iou += iou;
        ++images;
        const cv::Rect box = cv::boundingRect(mask), exact_box = cv::boundingRect(exact.Mask());
        EXPECT_LE(std::abs(box.x - exact_box.x), 1);
        EXPECT_LE(std::abs(box.y - exact_box.y), 1);
        EXPECT_LE(std::abs(box.br().x - exact_box.br().x), 1);
        EXPECT_LE(std::abs(box.br().y - exact_box.br().y), 1);
        EXPECT_EQ(drawn & box, box);
        // Every joint projects inside both masks.
        for (int j = 0; j < joints.cols(); ++j) {
          Eigen::Vector2d pixel;
          ASSERT_TRUE(camera.Project(joints.col(j), &pixel));
          const cv::Point p(static_cast<int>(std::lround(pixel.x())), static_cast<int>(std::lround(pixel.y())));
          ASSERT_TRUE(cv::Rect(0, 0, 320, 240).contains(p));
          EXPECT_EQ(mask.at<uint8_t>(p), 255) << walk.skeleton.bones[j].name << " frame " << frame;
          EXPECT_NE(exact.part.at<uint8_t>(p), BodyImage::kNoPart) << walk.skeleton.bones[j].name;
        }
      }
    }
  }
  mean_iou /= images;
  std::printf("fast vs exact silhouette over %d images: mean IoU %.4f, worst %.4f\n", images,
              mean_iou, worst_iou);
  EXPECT_GT(mean_iou, 0.95);
  EXPECT_GT(worst_iou, 0.92);
}

}  // namespace
}  // namespace jgpm
