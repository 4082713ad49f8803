// The tracker's likelihood against oracles: its pixel counts equal brute-force counts of
// the same images; on exact silhouettes of a real walk it is lowest at the true body and
// grows as the body is moved, turned or taken to another phase of the walk; and the bodies
// a one-sided score would accept (shrunk into the mask, legs collapsed onto each other)
// cost more than the true one; a body half beyond the image's edge is judged by what the
// image shows.
#include "tracker/filter/likelihood.h"

#include <cmath>
#include <cstdio>
#include <utility>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "io/mocap/amc.h"
#include "io/mocap/asf.h"
#include "io/mocap/kinematics.h"
#include "test_support.h"
#include "tracker/body/body_model.h"
#include "tracker/body/ray_caster.h"
#include "tracker/body/shadow_oracle.h"
#include "tracker/clip/clip_body.h"

namespace jgpm {
namespace {

struct Scene {
  Skeleton skeleton;
  Motion motion;
  std::vector<Camera> cameras;
};

const Scene& Walk() {
  static const Scene scene = [] {
    Scene s;
    s.skeleton = ReadAsf(test::CmuRoot() / "subjects/35/35.asf");
    s.motion = ReadAmc(test::CmuRoot() / "subjects/35/35_01.amc", s.skeleton);
    const Eigen::Matrix3Xd first = Kinematics(s.skeleton).Compute(s.motion.Frame(120));
    const Eigen::Vector3d at(first(0, 0), 900, first(2, 0));
    s.cameras.push_back(LookAtCamera("side", 320, 240, 330, at + Eigen::Vector3d(4200, 600, 0), at));
    s.cameras.push_back(LookAtCamera("front", 320, 240, 330, at + Eigen::Vector3d(300, 600, 4200), at));
    s.cameras[1].distortion = {-0.15, 0.03, 0, 0, 0};
    return s;
  }();
  return scene;
}

std::vector<Capsule> Body(const Scene& s, const Eigen::Matrix3Xd& joints, double size = 1) {
  std::vector<Capsule> capsules = BodyModel(s.skeleton, {}, "35.asf").Place(joints);
  for (Capsule& c : capsules) c.radius_from_mm *= size, c.radius_to_mm *= size;
  return capsules;
}

// Exact silhouettes (the ray caster) of frame `f` in every camera, with regions about them.
std::vector<CameraObservation> Observe(const Scene& s, const SilhouetteLikelihood& likelihood, int f) {
  const Eigen::Matrix3Xd joints = Kinematics(s.skeleton).Compute(s.motion.Frame(f));
  std::vector<CameraObservation> out;
  for (const Camera& camera : s.cameras) {
    BodyImage image;
    RayCaster(camera).Render(Body(s, joints), &image);
    const cv::Mat mask = image.Mask();
    cv::Rect box = cv::boundingRect(mask);
    box = cv::Rect(box.x - 20, box.y - 20, box.width + 40, box.height + 40);
    out.push_back(likelihood.Observe(mask, box));
  }
  return out;
}

TEST(Likelihood, CountsEqualBruteForce) {
  const Scene& s = Walk();
  const SilhouetteLikelihood likelihood(s.cameras);
  const std::vector<CameraObservation> observed = Observe(s, likelihood, 120);
  // A body off from the truth (another frame, moved): something in every count.
  Eigen::Matrix3Xd joints = Kinematics(s.skeleton).Compute(s.motion.Frame(135));
  joints.colwise() += Eigen::Vector3d(40, 0, -30);
  const std::vector<Capsule> body = Body(s, joints);
  SilhouetteLikelihood::Workspace workspace = likelihood.NewWorkspace();
  std::vector<CameraScore> scores;
  likelihood.Cost(body, observed, &workspace, &scores);
  const cv::Mat grow = cv::getStructuringElement(cv::MORPH_RECT, cv::Size(3, 3));
  for (size_t c = 0; c < s.cameras.size(); ++c) {
    BitMask bits(s.cameras[c].width, s.cameras[c].height);
    BitSilhouetteRenderer(s.cameras[c]).Draw(body, &bits);
    const cv::Mat model = bits.ToMat();
    cv::Mat region = cv::Mat::zeros(model.size(), CV_8UC1);
    region(observed[c].region()).setTo(255);
    const cv::Mat seen = observed[c].mask() & region;
    cv::Mat model_grown, seen_grown;
    cv::dilate(model, model_grown, grow);
    cv::dilate(seen, seen_grown, grow);
    EXPECT_EQ(scores[c].model_px, cv::countNonZero(model)) << c;
    EXPECT_EQ(scores[c].model_rows, cv::boundingRect(model).height) << c;
    EXPECT_EQ(scores[c].observed_px, cv::countNonZero(seen)) << c;
    EXPECT_EQ(scores[c].overlap_px, cv::countNonZero(model & seen)) << c;
    EXPECT_EQ(scores[c].outside_px, cv::countNonZero(model & ~seen_grown)) << c;
    EXPECT_EQ(scores[c].unexplained_px, cv::countNonZero(seen & ~model_grown)) << c;
    EXPECT_GT(scores[c].outside_px, 10);
    EXPECT_GT(scores[c].unexplained_px, 10);
    // And the workspace is blank again for the next body.
    EXPECT_EQ(workspace.canvas[c].Count(), 0);
  }
}

TEST(Likelihood, LowestAtTheTruthAndGrowingAwayFromIt) {
  const Scene& s = Walk();
  const SilhouetteLikelihood likelihood(s.cameras);
  const int f = 120;
  const std::vector<CameraObservation> observed = Observe(s, likelihood, f);
  const Kinematics kinematics(s.skeleton);
  const Eigen::Matrix3Xd truth = kinematics.Compute(s.motion.Frame(f));
  SilhouetteLikelihood::Workspace workspace = likelihood.NewWorkspace();
  auto cost = [&](const Eigen::Matrix3Xd& joints, double size = 1) {
    return likelihood.Cost(Body(s, joints, size), observed, &workspace);
  };
  const double best = cost(truth);
  // Moved along the floor, turned about the vertical through the root, later in the walk
  // (the root kept, so only the pose's phase differs).
  std::vector<double> moved, turned, phased;
  for (double d : {0.0, 25.0, 60.0, 120.0, 250.0}) {
    Eigen::Matrix3Xd j = truth;
    j.colwise() += Eigen::Vector3d(d, 0, 0.5 * d);
    moved.push_back(cost(j));
  }
  for (double degrees : {0.0, 6.0, 15.0, 35.0, 70.0}) {
    const Eigen::Matrix3d r = AxisRotation(Axis::kY, degrees);
    turned.push_back(cost((r * (truth.colwise() - truth.col(0))).colwise() + truth.col(0)));
  }
  for (int k : {0, 3, 8, 16, 30}) {
    Eigen::Matrix3Xd j = kinematics.Compute(s.motion.Frame(f + k));
    j.colwise() += truth.col(0) - j.col(0);
    phased.push_back(cost(j));
  }
  for (const auto* series : {&moved, &turned, &phased}) {
    EXPECT_DOUBLE_EQ((*series)[0], best);
    for (size_t i = 1; i < series->size(); ++i) EXPECT_GT((*series)[i], (*series)[i - 1]) << "step " << i;
  }
  // What a one-sided score accepts: a body shrunk into the mask (thinner limbs, or all of
  // it smaller, standing where it stood), and both legs in one place.
  EXPECT_LT(best, 0.02);
  EXPECT_GT(cost(truth, 0.8), best + 0.015);
  Eigen::Matrix3Xd smaller = truth;
  const Eigen::Vector3d floor(truth(0, 0), 0, truth(2, 0));
  smaller = (0.85 * (truth.colwise() - floor)).colwise() + floor;
  EXPECT_GT(cost(smaller, 0.85), best + 0.1);
  Eigen::Matrix3Xd collapsed = truth;
  for (const char* side : {"hipjoint", "femur", "tibia", "foot", "toes"}) {
    const int left = s.skeleton.FindBone(std::string("l") + side), right = s.skeleton.FindBone(std::string("r") + side);
    const Eigen::Vector3d hips = truth.col(s.skeleton.FindBone("rhipjoint")) - truth.col(s.skeleton.FindBone("lhipjoint"));
    collapsed.col(right) = truth.col(left) + hips;  // the right leg where the left one is, at its own hip
  }
  EXPECT_GT(cost(collapsed), best + 0.1);
}

// Masks the tracker's body cannot explain exactly: another person's build in a coat and
// with a bag, or in a skirt (tracker/clip/clip_body.h), ray cast. The true pose of the
// tracker's body still costs less than the bodies a loose score would take for it: both
// legs in one place, a smaller person, one half a cycle on.
// Masks that keep the walker's shadow (a segmentation without shadow removal): the exact
// silhouette and the floor pixels whose way to the light enters a part (the floor at the
// lowest foot). Unexplained, the shadow is most of the true body's cost, which anything that
// reaches into it lowers (on the harsh clips, legs hidden behind a table); drawn with each
// body, it is evidence for the truth, which costs least.
TEST(Likelihood, AShadowInTheMasksIsExplainedByTheBodysOwnShadow) {
  const Scene& s = Walk();
  const int f = 120;
  const Eigen::Matrix3Xd truth = Kinematics(s.skeleton).Compute(s.motion.Frame(f));
  const double floor = truth.row(1).minCoeff() - 30;
  // From the front camera's side, 45 degrees up: the shadow falls behind the walker, away
  // from that camera, along the floor beside the legs in the side camera's view.
  const Eigen::Vector3d light = Eigen::Vector3d(0.2, 1, 0.9).normalized();
  SilhouetteLikelihood likelihood(s.cameras);
  std::vector<CameraObservation> observed;
  for (const Camera& camera : s.cameras) {
    BodyImage image;
    RayCaster(camera).Render(Body(s, truth), &image);
    cv::Mat mask = image.Mask();
    test::AddRayCastShadow(camera, Body(s, truth), light, floor, &mask);
    // The region holds the shadow: the tracker's grows the body's box by 40% each way.
    const cv::Rect box = cv::boundingRect(mask);
    observed.push_back(likelihood.Observe(mask, cv::Rect(box.x - 20, box.y - 20, box.width + 40, box.height + 40)));
  }
  SilhouetteLikelihood::Workspace workspace = likelihood.NewWorkspace();
  // The body moved `d` mm along the floor towards where its shadow falls.
  const Eigen::Vector2d away = -Eigen::Vector2d(light.x(), light.z()).normalized();
  const auto cost = [&](double d, const Eigen::Vector3d* under) {
    Eigen::Matrix3Xd j = truth;
    j.colwise() += Eigen::Vector3d(d * away.x(), 0, d * away.y());
    return likelihood.CostUnder(under, Body(s, j), observed, &workspace);
  };
  likelihood.SetShadow(std::nullopt, floor);
  const double bare_truth = cost(0, nullptr), shadowed_truth = cost(0, &light);
  std::printf("the true body costs %.3f without its shadow, %.3f with it\n", bare_truth, shadowed_truth);
  EXPECT_LT(shadowed_truth, 0.25 * bare_truth);
  for (double d : {60.0, 120.0, 200.0, 300.0}) {
    EXPECT_GT(cost(d, &light), shadowed_truth + 0.01) << d;
    EXPECT_GT(cost(-d, &light), shadowed_truth + 0.01) << -d;
  }
  // The light set is the one Cost draws.
  likelihood.SetShadow(light, floor);
  EXPECT_DOUBLE_EQ(likelihood.Cost(Body(s, truth), observed, &workspace), shadowed_truth);
}

TEST(Likelihood, TheTruthStillWinsOnMasksOfAnotherBody) {
  const Scene& s = Walk();
  const SilhouetteLikelihood likelihood(s.cameras);
  const int f = 120;
  const Kinematics kinematics(s.skeleton);
  const Eigen::Matrix3Xd truth = kinematics.Compute(s.motion.Frame(f));
  for (const auto& [clothing, bag] : {std::pair{Clothing::kCoat, true}, std::pair{Clothing::kSkirt, false}}) {
    SCOPED_TRACE(std::string(ClothingName(clothing)));
    ClipBodyOptions other;
    other.body_seed = 5;
    other.clothing = clothing;
    other.bag = bag;
    const ClipBody body(s.skeleton, other, "35.asf");
    std::vector<Capsule> dressed;
    body.Place(truth, &dressed);
    std::vector<CameraObservation> observed;
    for (const Camera& camera : s.cameras) {
      BodyImage image;
      RayCaster(camera).Render(dressed, &image);
      const cv::Mat mask = image.Mask();
      cv::Rect box = cv::boundingRect(mask);
      observed.push_back(likelihood.Observe(mask, {box.x - 20, box.y - 20, box.width + 40, box.height + 40}));
    }
    SilhouetteLikelihood::Workspace workspace = likelihood.NewWorkspace();
    auto cost = [&](const Eigen::Matrix3Xd& joints, double size = 1) {
      return likelihood.Cost(Body(s, joints, size), observed, &workspace);
    };
    const double best = cost(truth);
    Eigen::Matrix3Xd collapsed = truth;
    for (const char* side : {"hipjoint", "femur", "tibia", "foot", "toes"}) {
      const int left = s.skeleton.FindBone(std::string("l") + side), right = s.skeleton.FindBone(std::string("r") + side);
      const Eigen::Vector3d hips = truth.col(s.skeleton.FindBone("rhipjoint")) - truth.col(s.skeleton.FindBone("lhipjoint"));
      collapsed.col(right) = truth.col(left) + hips;
    }
    const Eigen::Vector3d floor(truth(0, 0), 0, truth(2, 0));
    const Eigen::Matrix3Xd smaller = (0.85 * (truth.colwise() - floor)).colwise() + floor;
    Eigen::Matrix3Xd later = kinematics.Compute(s.motion.Frame(f + 16));  // half a step on
    later.colwise() += truth.col(0) - later.col(0);
    std::printf("truth %.3f, legs collapsed %.3f, 15%% smaller %.3f, half a step on %.3f\n", best, cost(collapsed),
                cost(smaller, 0.85), cost(later));
    EXPECT_GT(best, 0.05);  // the masks are not the tracker's body
    EXPECT_GT(cost(collapsed), best);
    EXPECT_GT(cost(smaller, 0.85), best);
    EXPECT_GT(cost(later), best);
  }
}

// A camera whose segmentation lost the person (a blank mask where three cameras see him):
// unbounded, drawing the body there costs |S| / 150 (here about 300) against the good
// views' fractions, so a body out of that camera's view, badly placed for the others, won.
// Bounded, the camera costs at most 2 + outline_weight, and the three good views decide.
TEST(Likelihood, ABlankCameraCannotOutvoteThreeGoodOnes) {
  const Scene& s = Walk();
  const Eigen::Matrix3Xd truth = Kinematics(s.skeleton).Compute(s.motion.Frame(120));
  const Eigen::Vector3d at(truth(0, 0), 900, truth(2, 0));
  std::vector<Camera> cameras = s.cameras;
  cameras.push_back(LookAtCamera("back", 320, 240, 330, at + Eigen::Vector3d(-4200, 600, 300), at));
  // A fourth camera narrow on the person: 900 mm aside, the body leaves its view.
  cameras.push_back(LookAtCamera("close", 320, 240, 1500, at + Eigen::Vector3d(200, 200, -3000), at));
  Eigen::Matrix3Xd aside = truth;
  aside.colwise() += Eigen::Vector3d(900, 0, 0);
  for (bool bounded : {true, false}) {
    LikelihoodOptions options;
    options.bound_cameras = bounded;
    const SilhouetteLikelihood likelihood(cameras, options);
    std::vector<CameraObservation> observed;
    for (size_t c = 0; c < cameras.size(); ++c) {
      BodyImage image;
      RayCaster(cameras[c]).Render(Body(s, truth), &image);
      const cv::Mat mask = c + 1 == cameras.size() ? cv::Mat(cv::Mat::zeros(240, 320, CV_8UC1)) : image.Mask();
      observed.push_back(likelihood.Observe(mask, {0, 0, 320, 240}));
    }
    SilhouetteLikelihood::Workspace workspace = likelihood.NewWorkspace();
    std::vector<CameraScore> scores;
    const double at_truth = likelihood.Cost(Body(s, truth), observed, &workspace, &scores);
    const double blank_camera = scores.back().cost;
    const double moved = likelihood.Cost(Body(s, aside), observed, &workspace, &scores);
    ASSERT_EQ(scores.back().model_px, 0);  // out of the blank camera's view
    std::printf("%s: truth %.2f (blank camera %.2f), 900 mm aside %.2f\n", bounded ? "bounded" : "unbounded", at_truth,
                blank_camera, moved);
    if (bounded) {
      EXPECT_LE(blank_camera, 2 + options.outline_weight);
      EXPECT_LT(at_truth, moved);
    } else {
      EXPECT_GT(at_truth, moved);  // what the bound is for
    }
  }
}

// A region wholly outside the image (the person expected beyond its border) while the body
// is drawn inside it: the packed region masks have the image's size (they had none, and
// the counts read past them) and the body costs what it costs against no foreground.
TEST(Likelihood, ARegionOutsideTheImageIsAnEmptyRegion) {
  const Scene& s = Walk();
  const SilhouetteLikelihood likelihood(s.cameras);
  const Eigen::Matrix3Xd truth = Kinematics(s.skeleton).Compute(s.motion.Frame(120));
  std::vector<CameraObservation> observed = Observe(s, likelihood, 120);
  const cv::Mat mask = observed[0].mask().clone();
  observed[0] = likelihood.Observe(mask, {1000, 1000, 50, 50});
  ASSERT_EQ(observed[0].region_bits().width(), 320);
  ASSERT_EQ(observed[0].region_bits_grown().height(), 240);
  EXPECT_EQ(observed[0].region_count(), 0);
  std::vector<CameraObservation> blank = observed;
  blank[0] = likelihood.Observe(cv::Mat::zeros(240, 320, CV_8UC1), {0, 0, 320, 240});
  SilhouetteLikelihood::Workspace workspace = likelihood.NewWorkspace();
  std::vector<CameraScore> nowhere, nothing;
  likelihood.Cost(Body(s, truth), observed, &workspace, &nowhere);
  likelihood.Cost(Body(s, truth), blank, &workspace, &nothing);
  EXPECT_GT(nowhere[0].model_px, 500);
  EXPECT_EQ(nowhere[0].overlap_px, 0);
  EXPECT_EQ(nowhere[0].cost, nothing[0].cost);
}

// A walker half out of the image (leaving a webcam's view at its side, feet below its
// bottom edge): the image shows nothing of what is beyond its edges, so the true body
// costs there what it costs in full view, and less than the body moved 60 mm into the
// image or out of it. The outline's points beyond the edges counted as far from any
// foreground, which pulled a leaving walker back into the view and turned them 20-35
// degrees (realism 35_16-all-webcam).
TEST(Likelihood, WhatIsBeyondTheImagesEdgesIsNoEvidence) {
  const Scene& s = Walk();
  const Eigen::Matrix3Xd truth = Kinematics(s.skeleton).Compute(s.motion.Frame(120));
  const Camera& full = s.cameras[0];  // 4.2 m to the side (+x), looking along -x
  Eigen::Vector2d root, foot;
  ASSERT_TRUE(full.Project(truth.col(0), &root));
  ASSERT_TRUE(full.Project(truth.col(s.skeleton.FindBone("ltibia")), &foot));
  Camera side = full, bottom = full;
  side.cx += full.width - root.x();      // the root on the right edge: half the body beyond it
  bottom.cy += full.height - foot.y();   // the knees on the bottom edge: shins and feet beyond it
  const Eigen::Vector3d right = full.cam_from_world_rotation.row(0).transpose();
  struct Cut {
    const char* name;
    Camera camera;
    Eigen::Vector3d into_view;  // a move that brings more of the body into the image
  };
  for (const Cut& cut : {Cut{"side", side, -60 * right}, Cut{"bottom", bottom, Eigen::Vector3d(0, 60, 0)}}) {
    SCOPED_TRACE(cut.name);
    const SilhouetteLikelihood likelihood({cut.camera});
    BodyImage image;
    RayCaster(cut.camera).Render(Body(s, truth), &image);
    const cv::Mat mask = image.Mask();
    const std::vector<CameraObservation> observed = {likelihood.Observe(mask, {0, 0, full.width, full.height})};
    ASSERT_GT(cv::countNonZero(mask), 300);
    SilhouetteLikelihood::Workspace workspace = likelihood.NewWorkspace();
    std::vector<CameraScore> scores;
    const double at_truth = likelihood.Cost(Body(s, truth), observed, &workspace, &scores);
    EXPECT_LT(scores[0].outline, 0.05);
    EXPECT_LT(at_truth, 0.05);
    Eigen::Matrix3Xd moved = truth;
    moved.colwise() += cut.into_view;
    const double into_view = likelihood.Cost(Body(s, moved), observed, &workspace);
    moved = truth;
    moved.colwise() -= cut.into_view;
    const double out_of_view = likelihood.Cost(Body(s, moved), observed, &workspace);
    std::printf("%s edge: truth %.3f (outline %.3f), 60 mm into the view %.3f, out of it %.3f\n", cut.name,
                at_truth, scores[0].outline, into_view, out_of_view);
    EXPECT_GT(into_view, at_truth + 0.02);
    EXPECT_GT(out_of_view, at_truth + 0.02);
  }
}

TEST(Likelihood, EmptyMasksAndNothingDrawnAreFinite) {
  const Scene& s = Walk();
  const SilhouetteLikelihood likelihood(s.cameras);
  const cv::Mat empty = cv::Mat::zeros(240, 320, CV_8UC1);
  std::vector<CameraObservation> nobody = {likelihood.Observe(empty, {0, 0, 320, 240}),
                                           likelihood.Observe(empty, {0, 0, 320, 240})};
  SilhouetteLikelihood::Workspace workspace = likelihood.NewWorkspace();
  const Eigen::Matrix3Xd truth = Kinematics(s.skeleton).Compute(s.motion.Frame(0));
  const double drawn = likelihood.Cost(Body(s, truth), nobody, &workspace);
  EXPECT_TRUE(std::isfinite(drawn));
  EXPECT_GT(drawn, 1.0);  // a body where nobody is costs
  EXPECT_EQ(likelihood.Cost({}, nobody, &workspace), 0.0);  // nobody where nobody is does not
}

}  // namespace
}  // namespace jgpm
