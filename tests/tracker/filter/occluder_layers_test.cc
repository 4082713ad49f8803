// Painted occluders in depth (tracker/filter/occluder_layers.h) against the scene that was
// painted: a pillar and a table projected through a known camera. An object's distance is
// its nearest foot's (unseen for one cut by the image's edge or above the horizon); it
// hides a body behind it, not one in front; and the likelihood judges a body against the
// observation made with exactly the objects in front of it hidden: a body drawn in front
// of a pillar where nobody is seen is charged for it (it was not while every painted pixel
// was hidden for every body), one behind it is not.
#include "tracker/filter/occluder_layers.h"

#include <cmath>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "tracker/body/ray_caster.h"
#include "tracker/filter/likelihood.h"

namespace jgpm {
namespace {

// 2.5 m up, looking down the floor along +z.
Camera High() {
  return LookAtCamera("high", 320, 240, 300, Eigen::Vector3d(0, 2500, 0), Eigen::Vector3d(0, 0, 6000));
}

// The image of a box [x0, x1] x [y0, y1] x [z0, z1] (mm), filled.
void PaintBox(const Camera& camera, Eigen::Vector3d lo, Eigen::Vector3d hi, cv::Mat* painting) {
  std::vector<cv::Point> corners;
  for (int i = 0; i < 8; ++i) {
    const Eigen::Vector3d p((i & 1) ? hi.x() : lo.x(), (i & 2) ? hi.y() : lo.y(), (i & 4) ? hi.z() : lo.z());
    Eigen::Vector2d pixel;
    EXPECT_TRUE(camera.Project(p, &pixel));
    corners.emplace_back(static_cast<int>(std::lround(pixel.x())), static_cast<int>(std::lround(pixel.y())));
  }
  std::vector<cv::Point> hull;
  cv::convexHull(corners, hull);
  cv::fillConvexPoly(*painting, hull, cv::Scalar(255));
}

constexpr double kTableFront = 3000, kTableBack = 3800, kTableTop = 750;
constexpr double kPillarX = 1500, kPillarFront = 4000;

// A table (top 1.2 x 0.8 m at 0.75 m, four legs) ahead of the camera and a pillar to its
// right, farther.
cv::Mat Painting(const Camera& camera) {
  cv::Mat painting = cv::Mat::zeros(camera.height, camera.width, CV_8UC1);
  PaintBox(camera, {-600, kTableTop - 40, kTableFront}, {600, kTableTop, kTableBack}, &painting);
  for (double x : {-580.0, 540.0})
    for (double z : {kTableFront, kTableBack - 40})
      PaintBox(camera, {x, 0, z}, {x + 40, kTableTop, z + 40}, &painting);
  PaintBox(camera, {kPillarX - 200, 0, kPillarFront}, {kPillarX + 200, 2400, kPillarFront + 400}, &painting);
  return painting;
}

// One row's depth on the floor at the object's foot (d^2 / (f h), and a third for the
// camera's tilt), for the distance's tolerance: the lowest pixel's lower edge is within a
// row of the foot.
double RowDepthMm(double distance_mm) { return distance_mm * distance_mm / (300.0 * 2500.0) * 1.3; }

// The table and the pillar, told apart by where their pixels are.
struct Objects {
  PaintedObject table, pillar;
};
Objects Split(const Camera& camera) {
  const std::vector<PaintedObject> objects = SplitPainting(Painting(camera), camera);
  EXPECT_EQ(objects.size(), 2u);
  const bool first_is_table = objects[0].pixels.at<uint8_t>(150, 160) != 0;
  return {objects[first_is_table ? 0 : 1], objects[first_is_table ? 1 : 0]};
}

TEST(OccluderLayers, EachObjectStandsAtItsNearestFoot) {
  const Camera camera = High();
  const Objects o = Split(camera);
  // The table's lowest row is both front legs' feet, its middle straight ahead; the
  // pillar's is its front edge, its middle at the pillar's x.
  EXPECT_NEAR(o.table.distance_mm, kTableFront, RowDepthMm(kTableFront));
  const double pillar_foot = std::hypot(kPillarX, kPillarFront);
  EXPECT_NEAR(o.pillar.distance_mm, pillar_foot, RowDepthMm(pillar_foot));
  EXPECT_EQ(cv::countNonZero(o.table.pixels & o.pillar.pixels), 0);
  EXPECT_EQ(cv::countNonZero(o.table.pixels | o.pillar.pixels), cv::countNonZero(Painting(camera)));
  // A pillar so near that the image's bottom edge cuts it: its foot is unseen.
  cv::Mat near = cv::Mat::zeros(240, 320, CV_8UC1);
  PaintBox(camera, {-1200, 0, 1800}, {-900, 2400, 2000}, &near);
  const std::vector<PaintedObject> cut = SplitPainting(near, camera);
  ASSERT_EQ(cut.size(), 1u);
  ASSERT_EQ(cv::boundingRect(cut[0].pixels).br().y, 240);
  EXPECT_TRUE(std::isinf(cut[0].distance_mm));
  // Seen level from 1.5 m, a sign whose lower edge is above the horizon stands nowhere on
  // the floor.
  const Camera level = LookAtCamera("level", 320, 240, 300, Eigen::Vector3d(0, 1500, 0), Eigen::Vector3d(0, 1500, 6000));
  cv::Mat sign = cv::Mat::zeros(240, 320, CV_8UC1);
  sign(cv::Rect(100, 20, 60, 40)).setTo(255);
  const std::vector<PaintedObject> hanging = SplitPainting(sign, level);
  ASSERT_EQ(hanging.size(), 1u);
  EXPECT_TRUE(std::isinf(hanging[0].distance_mm));
  EXPECT_TRUE(SplitPainting(cv::Mat(), level).empty());
}

TEST(OccluderLayers, HidesOnlyABodyBehindIt) {
  const Camera camera = High();
  const Eigen::Vector3d eye = camera.CentreInWorld();
  const Objects o = Split(camera);
  const auto at = [](double x, double z) { return Eigen::Vector3d(x, 0, z); };
  EXPECT_TRUE(Hides(o.table, at(0, 4800), eye));
  EXPECT_FALSE(Hides(o.table, at(0, 2500), eye));
  EXPECT_TRUE(Hides(o.pillar, at(kPillarX, 5000), eye));
  EXPECT_TRUE(Hides(o.pillar, at(kPillarX + 400, 5000), eye)) << "behind, beside it: an arm may be hidden";
  EXPECT_FALSE(Hides(o.pillar, at(kPillarX, 3500), eye));
  PaintedObject hanging = o.pillar;
  hanging.distance_mm = std::numeric_limits<double>::infinity();
  EXPECT_TRUE(Hides(hanging, at(kPillarX, 500), eye));
  // The floor point is the body's centre's, heights left out.
  const std::vector<Capsule> body = {{{100, 200, 4000}, {300, 1400, 4200}, 150, 150}};
  EXPECT_TRUE(FloorPointUnder(body).isApprox(Eigen::Vector3d(200, 0, 4100)));
}

// A walker at (x, z): legs and trunk, and a head.
std::vector<Capsule> Person(double x, double z) {
  return {{{x, 200, z}, {x, 1380, z}, 170, 170}, {{x, 1520, z}, {x, 1600, z}, 100, 100}};
}

// `body` scaled about `eye` by `a`: the same image, a times as far.
std::vector<Capsule> Scaled(std::vector<Capsule> body, const Eigen::Vector3d& eye, double a) {
  for (Capsule& c : body) {
    c.from_mm = eye + a * (c.from_mm - eye);
    c.to_mm = eye + a * (c.to_mm - eye);
    c.radius_from_mm *= a, c.radius_to_mm *= a;
  }
  return body;
}

TEST(OccluderLayers, TheLikelihoodHidesOnlyWhatIsInFront) {
  const Camera camera = High();
  const Eigen::Vector3d eye = camera.CentreInWorld();
  const cv::Mat painting = Painting(camera);
  const Objects o = Split(camera);
  // A walker half behind the pillar: the mask is what the pillar leaves of them.
  const std::vector<Capsule> truth = Person(1530, 5200);
  BodyImage image;
  RayCaster(camera).Render(truth, &image);
  cv::Mat mask = image.Mask();
  mask.setTo(0, o.pillar.pixels);
  ASSERT_GT(cv::countNonZero(mask), 300);
  ASSERT_GT(cv::countNonZero(image.Mask() & o.pillar.pixels), 300);
  // The same image from a body in front of the pillar: its half over the pillar, where
  // nobody is seen, would be in view.
  const std::vector<Capsule> in_front = Scaled(truth, eye, 3600.0 / 5200);
  ASSERT_FALSE(Hides(o.pillar, FloorPointUnder(in_front), eye));

  SilhouetteLikelihood likelihood({camera});
  SilhouetteLikelihood::Workspace workspace = likelihood.NewWorkspace();
  const cv::Rect region(0, 0, 320, 240);
  const auto cost = [&](const std::vector<Capsule>& body, const CameraObservation& observation) {
    return likelihood.Cost(body, {observation}, &workspace);
  };
  // by_subset[s]: the observation with the objects whose bit is set in s hidden (bit 0 the
  // table, bit 1 the pillar); all of them, the painting.
  const CameraObservation everything = likelihood.Observe(mask, region, painting);
  std::vector<CameraObservation> by_subset = {likelihood.Observe(mask, region), likelihood.Observe(mask, region, o.table.pixels),
                                              likelihood.Observe(mask, region, o.pillar.pixels)};
  CameraObservation layered = likelihood.Observe(mask, region, painting);
  layered.SetPaintedObjects({o.table, o.pillar}, by_subset);
  ASSERT_TRUE(layered.layered());

  // The oracle: the cost against the observation made with exactly the objects in front.
  const std::vector<Capsule> beside = Person(900, 3000);
  for (const std::vector<Capsule>* body : {&truth, &in_front, &beside}) {
    unsigned s = 0;
    if (Hides(o.table, FloorPointUnder(*body), eye)) s |= 1;
    if (Hides(o.pillar, FloorPointUnder(*body), eye)) s |= 2;
    EXPECT_DOUBLE_EQ(cost(*body, layered), cost(*body, s == 3 ? everything : by_subset[s]));
  }
  EXPECT_DOUBLE_EQ(cost(truth, layered), cost(truth, everything)) << "behind both: hidden as before";
  // With every painted pixel hidden for every body the two explain the mask alike; now the
  // one in front pays for its half over the pillar.
  EXPECT_NEAR(cost(in_front, everything), cost(truth, everything), 0.05);
  EXPECT_GT(cost(in_front, layered), cost(truth, layered) + 0.3);
}

}  // namespace
}  // namespace jgpm
