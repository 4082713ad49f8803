// The floor-reflection cut against the renderer that drew the reflection: on a glossy
// floor's observed masks it takes out the reflection (the observed pixels the same clip's
// matt floor does not have) and keeps the walker (the exact masks), seen from a camera 1 m
// up and from surveillance cameras; on a matt floor, and from the ring's cameras at chest
// height (where one view cannot tell), it cuts nothing. A hand-drawn figure seen by a level
// camera is cut at its feet, and only a floor glossy to most cameras is cut at all.
#include "tracker/frames/floor_reflection.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "calibration/camera.h"
#include "io/mocap/amc.h"
#include "io/mocap/asf.h"
#include "test_support.h"
#include "tracker/clip/synthetic_clip.h"
#include "tracker/frames/clip_source.h"

namespace jgpm {
namespace {

namespace fs = std::filesystem;

cv::Mat ReadMask(const fs::path& clip, const std::string& folder, const std::string& camera, int frame) {
  return cv::imread((clip / folder / camera / cv::format("%06d.png", frame)).string(), cv::IMREAD_GRAYSCALE);
}

struct Counts {
  int frames = 0, cut_frames = 0;
  long reflection = 0, reflection_cut = 0;  // observed glossy pixels the matt floor lacks
  long walker = 0, walker_cut = 0;          // observed pixels of the walker (exact masks)
  long body_cut = 0;                        // of them above the walker's lowest tenth (the feet)
  double worst_walker_share = 0;            // the most of one frame's walker cut
  double best_share = 0;                    // CutFloorReflections' best share, any frame
};

// Renders `trial` on a matt and a glossy floor with the same seed and cuts every observed
// mask of each.
std::pair<Counts, Counts> CutBoth(const std::string& trial, const RigOptions& rig) {
  const std::string subject = trial.substr(0, trial.find('_'));
  const ClipSource source{(test::CmuRoot() / "subjects" / subject / (subject + ".asf")).string(),
                          (test::CmuRoot() / "subjects" / subject / (trial + ".amc")).string()};
  const Skeleton skeleton = ReadAsf(source.asf);
  const Motion motion = ReadAmc(source.amc, skeleton);
  test::TempDir dir;
  ClipOptions options;
  options.max_frames = 40;
  options.rig = rig;
  options.contact_sheet = false;
  std::pair<Counts, Counts> counts;
  for (const double reflection : {0.0, 0.3}) {
    options.scene.reflection = reflection;
    const fs::path clip = dir.path() / (reflection > 0 ? "glossy" : "matt");
    const ClipSummary summary = RenderClip(skeleton, motion, source, {}, options, clip.string());
    Counts& c = reflection > 0 ? counts.second : counts.first;
    for (const Camera& camera : summary.cameras) {
      for (int k = 0; k < summary.frames; ++k) {
        const cv::Mat observed = ReadMask(clip, "observed", camera.name, k);
        if (observed.empty()) continue;  // a dropped frame
        const cv::Mat walker = ReadMask(clip, "masks", camera.name, k) & observed;
        const cv::Mat matt = ReadMask(dir.path() / "matt", "observed", camera.name, k);
        if (matt.empty()) ADD_FAILURE() << "no matt mask " << camera.name << " " << k;
        cv::Mat kept = observed;
        const ReflectionCut cut = CutFloorReflections(camera, &kept);
        const cv::Mat removed = observed & ~kept;
        EXPECT_EQ(cv::countNonZero(removed), cut.pixels);
        ++c.frames;
        c.cut_frames += cut.blobs > 0;
        c.best_share = std::max(c.best_share, cut.best_share);
        c.reflection += cv::countNonZero(observed & ~matt);
        c.reflection_cut += cv::countNonZero(removed & ~matt);
        const int own = cv::countNonZero(walker);
        if (own > 0) {
          // The rendered feet sink up to 40 mm into the floor (their capsules' radius about
          // joints 0-70 mm up), below the plane the reflection is mirrored in; and a foot
          // nearer the camera than the body's axis stands lower in the image. The body
          // above the feet must be kept.
          cv::Mat at;
          cv::findNonZero(walker, at);
          const cv::Rect extent = cv::boundingRect(at);
          const int feet = extent.y + extent.height - extent.height / 10;
          c.body_cut += cv::countNonZero(removed(cv::Rect(0, 0, removed.cols, feet)) & walker(cv::Rect(0, 0, removed.cols, feet)));
        }
        c.walker += own;
        c.walker_cut += cv::countNonZero(removed & walker);
        if (own > 0) c.worst_walker_share = std::max(c.worst_walker_share, cv::countNonZero(removed & walker) / double(own));
      }
    }
  }
  return counts;
}

void Report(const char* what, const Counts& c) {
  std::printf("%s: %d of %d frames cut; reflection %ld px, %.1f%% cut; walker %ld px, %.2f%% cut (worst frame %.1f%%, "
              "above the feet %ld px); best share %.2f\n",
              what, c.cut_frames, c.frames, c.reflection, c.reflection ? 100.0 * c.reflection_cut / c.reflection : 0.0,
              c.walker, c.walker ? 100.0 * c.walker_cut / c.walker : 0.0, 100 * c.worst_walker_share, c.body_cut,
              c.best_share);
}

RigOptions Rig(RigKind kind, int cameras, double height_mm = 1500) {
  RigOptions rig;
  rig.kind = kind;
  rig.num_cameras = cameras;
  rig.camera_height_mm = height_mm;
  return rig;
}

// `cut`: the reflection is cut from the glossy floor's masks; else the camera is at a
// height where a reflection and legs are not told apart, and nothing is cut.
void Expect(const std::string& trial, const RigOptions& rig, bool cut) {
  const auto [matt, glossy] = CutBoth(trial, rig);
  const std::string name = trial + " " + std::string(RigKindName(rig.kind)) + " " +
                           std::to_string(static_cast<int>(rig.camera_height_mm)) + " mm";
  Report((name + ", matt").c_str(), matt);
  Report((name + ", glossy").c_str(), glossy);
  // Nothing is cut from a matt floor's masks.
  EXPECT_EQ(matt.cut_frames, 0);
  // The reflection is mostly gone, the walker kept but for the bottom of the feet.
  ASSERT_GT(glossy.reflection, 1000);
  if (cut) {
    EXPECT_GT(glossy.reflection_cut, 0.8 * glossy.reflection);
  } else {
    EXPECT_EQ(glossy.cut_frames, 0);
  }
  EXPECT_LT(glossy.walker_cut, 0.03 * glossy.walker);
  EXPECT_LT(glossy.worst_walker_share, 0.1);
  EXPECT_LT(glossy.body_cut, 0.001 * glossy.walker);
}

// The lab's ring at 1.5 m, as the suites have it: between heights that tell, one camera at
// a time (the source checks two against each other: below).
TEST(FloorReflection, NotCutFromCamerasAtChestHeight) { Expect("07_03", Rig(RigKind::kRing, 2), false); }
TEST(FloorReflection, CutFromALowCamera) { Expect("07_03", Rig(RigKind::kRing, 2, 1000), true); }
TEST(FloorReflection, CutFromSurveillanceCameras) { Expect("39_13", Rig(RigKind::kSurveillance, 2), true); }
// A webcam's walker close by, cut by the image's edges: nothing cut either way.
TEST(FloorReflection, NothingCutFromAWebcamsWalker) {
  const auto [matt, glossy] = CutBoth("35_29", Rig(RigKind::kWebcam, 1));
  Report("35_29 webcam, matt", matt);
  EXPECT_EQ(matt.cut_frames, 0);
}

// A hand-drawn person seen by a level camera 1.2 m up, 4 m away: a body 400 mm wide to
// 1.45 m and a head 200 mm wide to 1.7 m, each pixel on when its centre's ray meets the
// figure's plane inside it; with its mirror image below the floor the cut leaves the
// person alone (to the row through the feet), and the person alone is not cut.
cv::Mat Figure(const Camera& camera, bool mirrored) {
  cv::Mat mask(camera.height, camera.width, CV_8UC1, cv::Scalar(0));
  const Eigen::Vector3d eye = camera.CentreInWorld();
  for (int v = 0; v < mask.rows; ++v) {
    for (int u = 0; u < mask.cols; ++u) {
      Eigen::Matrix2Xd pixel(2, 1);
      pixel << u, v;
      const Eigen::Vector3d ray = camera.PixelRaysInWorld(pixel).col(0);
      const Eigen::Vector3d at = eye + ray * (-eye.z() / ray.z());  // the plane z = 0
      const double y = mirrored ? std::abs(at.y()) : at.y();
      const bool body = y >= 0 && y <= 1450 && std::abs(at.x()) <= 200;
      const bool head = y > 1450 && y <= 1700 && std::abs(at.x()) <= 100;
      if (body || head) mask.at<uchar>(v, u) = 255;
    }
  }
  return mask;
}

TEST(FloorReflection, AMirroredFigureIsCutAtItsFeet) {
  const Camera level = LookAtCamera("c", 320, 240, 150, Eigen::Vector3d(30, 1200, -4000), Eigen::Vector3d(30, 1200, 0));
  const cv::Mat alone = Figure(level, false);
  cv::Mat both = Figure(level, true);
  ASSERT_GT(cv::countNonZero(both), 1.8 * cv::countNonZero(alone));
  const ReflectionCut cut = CutFloorReflections(level, &both);
  EXPECT_EQ(cut.blobs, 1);
  EXPECT_GT(cut.best_share, 0.95);
  // The feet are at row 165 (120 + 150 * 1200 / 4000): at most that row differs.
  EXPECT_LE(cv::countNonZero(both != alone), cv::countNonZero(alone.row(165)) + cv::countNonZero(alone.row(164)));
  cv::Mat untouched = alone.clone();
  EXPECT_EQ(CutFloorReflections(level, &untouched).blobs, 0);
  EXPECT_EQ(cv::countNonZero(untouched != alone), 0);
  // A camera below the floor sees no reflection under anyone.
  const Camera below = LookAtCamera("c", 320, 240, 150, Eigen::Vector3d(0, -500, -4000), Eigen::Vector3d(0, -500, 0));
  cv::Mat mask = Figure(level, true);
  EXPECT_EQ(CutFloorReflections(below, &mask).blobs, 0);
}

// Frames from a list, each camera's mask given.
class ListSource : public FrameSource {
 public:
  ListSource(std::vector<Camera> cameras, std::vector<std::vector<cv::Mat>> masks)
      : cameras_(std::move(cameras)), masks_(std::move(masks)) {}
  const std::vector<Camera>& cameras() const override { return cameras_; }
  double fps() const override { return 30; }
  int NumFrames() const override { return static_cast<int>(masks_.size()); }
  bool Next(Frame* frame) override {
    if (next_ >= masks_.size()) return false;
    *frame = Frame();
    frame->index = static_cast<int>(next_);
    for (const cv::Mat& mask : masks_[next_]) frame->masks.push_back(mask.clone());
    ++next_;
    return true;
  }

 private:
  std::vector<Camera> cameras_;
  std::vector<std::vector<cv::Mat>> masks_;
  size_t next_ = 0;
};

// A glossy floor is the scene's: with the figure's mirror in 11 of 12 frames every frame
// is cut, from the first (read ahead); with it in 3 of 12 (a shadow now and then) none is.
TEST(FloorReflection, OnlyAGlossyFloorIsCut) {
  const Camera level = LookAtCamera("c", 320, 240, 150, Eigen::Vector3d(30, 1200, -4000), Eigen::Vector3d(30, 1200, 0));
  const cv::Mat alone = Figure(level, false), both = Figure(level, true);
  for (const int mirrored : {11, 3}) {
    std::vector<std::vector<cv::Mat>> masks;
    for (int k = 0; k < 12; ++k) masks.push_back({k < mirrored ? both : alone});
    GlossyFloorOptions glossy;
    glossy.lookahead_frames = 12;  // all of them: decided before the first
    FloorReflectionSource source(std::make_unique<ListSource>(std::vector<Camera>{level}, masks), false, glossy);
    Frame frame;
    int cut = 0, k = 0;
    while (source.Next(&frame)) {
      // No frame keeps the mirror when glossy, none loses anything otherwise.
      if (mirrored == 11) {
        EXPECT_LE(cv::countNonZero(frame.masks[0] != alone), cv::countNonZero(alone.row(164)) + cv::countNonZero(alone.row(165))) << k;
      } else {
        EXPECT_EQ(cv::countNonZero(frame.masks[0] != masks[k][0]), 0) << k;
      }
      cut += cv::countNonZero(frame.masks[0] != masks[k][0]) > 0;
      ++k;
    }
    EXPECT_EQ(k, 12);
    EXPECT_EQ(cut, mirrored == 11 ? 11 : 0);
    EXPECT_EQ(source.frames_cut(), cut);
    EXPECT_EQ(source.Glossy(), mirrored == 11);
  }
  // Two cameras, the mirror in every frame of one and never in the other's (a shadow cast
  // towards one camera): the floor is not glossy, nothing is cut.
  std::vector<std::vector<cv::Mat>> masks(12, std::vector<cv::Mat>{both, alone});
  FloorReflectionSource source(std::make_unique<ListSource>(std::vector<Camera>{level, level}, masks), false);
  Frame frame;
  while (source.Next(&frame)) EXPECT_EQ(cv::countNonZero(frame.masks[0] != both), 0);
  EXPECT_FALSE(source.Glossy());
  EXPECT_EQ(source.frames_cut(), 0);
}

// Two cameras at chest height, each unable to tell alone: through the source, the feet
// under each one's mirror row are one place while the blobs' bottoms are not, so a glossy
// floor's reflections are cut; on the matt floor the proposals (hips, knees) disagree and
// nothing is.
TEST(FloorReflection, TwoCamerasAtChestHeightTellByWhereTheFeetAgree) {
  const ClipSource source{(test::CmuRoot() / "subjects/07/07.asf").string(),
                          (test::CmuRoot() / "subjects/07/07_03.amc").string()};
  const Skeleton skeleton = ReadAsf(source.asf);
  const Motion motion = ReadAmc(source.amc, skeleton);
  test::TempDir dir;
  ClipOptions options;
  options.max_frames = 40;
  options.rig = Rig(RigKind::kRing, 2);
  options.contact_sheet = false;
  for (const double reflection : {0.0, 0.3}) {
    options.scene.reflection = reflection;
    RenderClip(skeleton, motion, source, {}, options, (dir.path() / (reflection > 0 ? "glossy" : "matt")).string());
  }
  for (const char* floor : {"matt", "glossy"}) {
    const bool glossy = std::string(floor) == "glossy";
    FloorReflectionSource cut(std::make_unique<ClipFrameSource>(dir.path() / floor, ClipFrameSourceOptions{}), false);
    long reflection = 0, reflection_cut = 0, walker = 0, walker_cut = 0;
    Frame frame;
    while (cut.Next(&frame)) {
      for (size_t c = 0; c < frame.masks.size(); ++c) {
        const std::string& name = cut.cameras()[c].name;
        const cv::Mat observed = ReadMask(dir.path() / floor, "observed", name, frame.index);
        const cv::Mat matt = ReadMask(dir.path() / "matt", "observed", name, frame.index);
        const cv::Mat exact = ReadMask(dir.path() / floor, "masks", name, frame.index);
        const cv::Mat removed = observed & ~frame.masks[c];
        reflection += cv::countNonZero(observed & ~matt);
        reflection_cut += cv::countNonZero(removed & ~matt);
        walker += cv::countNonZero(exact & observed);
        walker_cut += cv::countNonZero(removed & exact);
      }
    }
    std::printf("%s, two cameras 1.5 m up: %d frames cut, reflection %ld px, %.1f%% cut; walker %.2f%% cut\n", floor,
                cut.frames_cut(), reflection, reflection ? 100.0 * reflection_cut / reflection : 0.0,
                100.0 * walker_cut / walker);
    EXPECT_EQ(cut.Glossy(), glossy);
    if (glossy) {
      EXPECT_GT(reflection_cut, 0.3 * reflection);  // 39%: the frames where both propose
      EXPECT_LT(walker_cut, 0.03 * walker);
    } else {
      EXPECT_EQ(cut.frames_cut(), 0);
    }
  }
}

}  // namespace
}  // namespace jgpm
