// Several people at once (`jgpm track --people all`, RunTrackJob) on rendered walkers whose
// truth is exact, scored by CLEAR MOT (tracker/run/mot_metrics.h): two walkers apart are two
// people with their poses; crossing, and one hidden behind the other, they keep their ids;
// a shadow and clutter start nobody; a walker who leaves the view ends, and so does one only
// a giant explains; one seed gives the same poses.json with one thread or two.
#include "tracker/filter/multi_tracker.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <memory>
#include <map>
#include <numbers>
#include <set>
#include <sstream>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "io/mocap/amc.h"
#include "io/mocap/asf.h"
#include "prior/model/model_file.h"
#include "prior/model/train.h"
#include "calibration/camera.h"
#include "prior/prior_test_support.h"
#include "test_support.h"
#include "tracker/clip/clip_scene.h"
#include "tracker/clip/synthetic_clip.h"
#include "tracker/run/track_job.h"

namespace jgpm {
namespace {

namespace fs = std::filesystem;

// Clips are 320x240: at 160x120 a crossing leaves each walker too few pixels of their own
// for the small prior below (MOTA 0.82 and a switch, against 1.0 at 320x240).
// An ML-JGPM torus prior from five training trials (as tracker_test's), made once.
struct Fixture {
  test::TempDir dir;
  fs::path model;
};
const Fixture& Shared() {
  static Fixture fixture;
  static const bool made = [] {
    fixture.model = fixture.dir.path() / "mljgpm.json";
    WriteModelFile(fixture.model, *test::TrainOnFirstWalks(ModelKind::kMljgpmTorus, 5, 5));
    return true;
  }();
  (void)made;
  return fixture;
}

ClipWalker Walker(const std::string& trial, ClipPlacement placement, uint64_t body_seed) {
  ClipWalker w;
  const std::string subject = trial.substr(0, trial.find('_'));
  w.source = {(test::CmuRoot() / "subjects" / subject / (subject + ".asf")).string(),
              (test::CmuRoot() / "subjects" / subject / (trial + ".amc")).string()};
  w.skeleton = ReadAsf(w.source.asf);
  w.motion = ReadAmc(w.source.amc, w.skeleton);
  w.body.body_seed = body_seed;
  w.placement = placement;
  return w;
}

// A clip of the walkers through the default ring (2 cameras, or `cameras`) at 320x240, or
// through `given` cameras.
fs::path Render(const std::vector<ClipWalker>& walkers, const fs::path& dir, int cameras = 2, int max_frames = 0,
                const std::function<void(ClipOptions*)>& more = {}, const std::vector<Camera>& given = {}) {
  ClipOptions clip;
  clip.rig.num_cameras = cameras;
  clip.max_frames = max_frames;
  clip.contact_sheet = false;
  if (more) more(&clip);
  RenderClip(walkers, given, clip, dir.string());
  return dir;
}

// A camera 4.5 m from the line z = 0 at a head's height (so that a head behind another is
// hidden by it), looking across the line at x = `look_x`, a field of view `across_mm` wide
// there.
Camera SideCamera(double look_x, double across_mm) {
  return LookAtCamera("cam0", 320, 240, 160 * 4500 / (across_mm / 2), {look_x, 1600, -4500}, {look_x, 1000, 0});
}

// A small budget: 150 particles x 4 layers.
TrackJobOptions Job(const fs::path& clip, int threads = 1, const fs::path& out = {}) {
  TrackJobOptions job;
  job.model = Shared().model.string();
  job.source.clip = clip.string();
  job.out = out.string();
  job.overlays = false;
  job.people = true;
  job.tracker.threads = threads;
  job.tracker.annealing.particles = 150;
  job.tracker.annealing.layers = 4;
  job.tracker.annealing.seed = 7;
  return job;
}

void Print(const char* what, const TrackJobResult& r) {
  const MotResult& m = *r.mot;
  std::printf("%-12s MOTA %.3f  MOTP %.0f mm  misses %d  false %d  switches %d  fragments %d  of %d; paired pose %.1f mm "
              "(14 joints); %.1f frames/s\n",
              what, m.mota, m.motp_mm, m.misses, m.false_positives, m.id_switches, m.fragmentations, m.truth,
              r.matched_bodytrack14 ? r.matched_bodytrack14->absolute_mm : -1.0,
              r.run.tracking_seconds > 0 ? r.people.size() / r.run.tracking_seconds : 0.0);
}

std::set<int> Ids(const TrackJobResult& r) {
  std::set<int> ids;
  for (const PeopleFrame& f : r.people)
    for (const PersonFrame& p : f.people) ids.insert(p.id);
  return ids;
}

// A clip of two walkers tracked as two people, no identity switched, with at least
// `mota` and the paired people's pose within `pose_mm` (bodytrack's 14 joints).
void ExpectTwoPeople(const TrackJobResult& r, double mota, double pose_mm) {
  EXPECT_EQ(r.mot->truth_tracks, 2);
  EXPECT_EQ(Ids(r).size(), 2u);
  EXPECT_GE(r.mot->mota, mota);
  EXPECT_EQ(r.mot->id_switches, 0);
  ASSERT_TRUE(r.matched_bodytrack14);
  EXPECT_LT(r.matched_bodytrack14->absolute_mm, pose_mm);
}

// Two walkers 2.5 m apart, walking the same way: two people, each with a pose near theirs.
// Measured: MOTA 0.975 (each confirmed after 2 frames), 54 mm over bodytrack's 14 joints
// (the one-person tracker_test's clip at 160x120 and the same budget: 80 mm).
TEST(MultiTracker, TwoWalkersApartAreTwoPeopleWithTheirPoses) {
  test::TempDir dir;
  const fs::path clip = Render({Walker("07_01", {true, 0, -1250, 0, 0}, 0), Walker("35_10", {true, 0, 1250, 0, 0}, 3)},
                               dir.path() / "apart");
  const TrackJobResult r = RunTrackJob(Job(clip));
  Print("apart", r);
  ExpectTwoPeople(r, 0.9, 130);
  // Both in view from the first frame and followed from it: their estimates from before
  // they were confirmed are in the frames they belong to (PeopleFrame::earlier), and both
  // are born there.
  ASSERT_FALSE(r.people.empty());
  EXPECT_EQ(r.people.front().people.size(), 2u);
  EXPECT_EQ(r.people.front().born.size(), 2u);
}

// The same two walkers sent across each other's path at the same moment: still two people,
// and each keeps its id through the crossing.
TEST(MultiTracker, WalkersCrossingKeepTheirIds) {
  test::TempDir dir;
  const fs::path clip = Render({Walker("07_01", {true, 0, 0, 0, 0}, 0), Walker("35_10", {true, 0, 0, 90, 0}, 3)},
                               dir.path() / "crossing");
  const TrackJobResult r = RunTrackJob(Job(clip));
  Print("crossing", r);
  EXPECT_GE(r.mot->mota, 0.9);
  EXPECT_EQ(r.mot->id_switches, 0);
  EXPECT_LE(Ids(r).size(), 3u);
}

// One camera beside the walk; a walker overtakes a slower one on a parallel line 1.2 m
// nearer the camera, so that the slower one is behind them for a while (the truth's visible
// pixels say how long): the hidden one keeps their id after. (Measured: MOTA 0.911; the
// hidden walker is lost for 8 frames and found again where they were.)
TEST(MultiTracker, AWalkerHiddenBehindAnotherKeepsTheirId) {
  test::TempDir dir;
  const fs::path clip = Render({Walker("07_01", {true, 0, -1200, 0, 0}, 0), Walker("07_04", {true, 0, 0, 0, 0}, 3)},
                               dir.path() / "hidden", 1, 0, {}, {SideCamera(0, 6000)});
  const ClipGroundTruth truth = ReadGroundTruth(clip / "ground_truth.json");
  // How many frames in a row a walker shows under half their usual pixels.
  int longest = 0, hidden = 0;
  for (const ClipPerson& p : truth.people) {
    std::vector<int> seen;
    for (const ClipPersonFrame& f : p.frames) seen.push_back(f.visible_px[0]);
    std::vector<int> sorted = seen;
    std::sort(sorted.begin(), sorted.end());
    const int usual = sorted[sorted.size() / 2];
    int run = 0;
    for (int s : seen) {
      run = 2 * s < usual ? run + 1 : 0;
      if (run > longest) longest = run, hidden = p.id;
    }
  }
  std::printf("walker %d is mostly hidden for %d frames in a row\n", hidden, longest);
  ASSERT_GE(longest, 10);
  const TrackJobResult r = RunTrackJob(Job(clip));
  Print("hidden", r);
  EXPECT_EQ(r.mot->id_switches, 0);
  EXPECT_GE(r.mot->mota, 0.8);
  // The tracked people at the clip's end are the ones of its start (once confirmed).
  ASSERT_GT(r.people.size(), 10u);
  std::set<int> first, last;
  for (const PersonFrame& p : r.people[10].people) first.insert(p.id);
  for (const PersonFrame& p : r.people.back().people)
    if (p.frame.status != TrackStatus::kLost) last.insert(p.id);
  EXPECT_EQ(first, last);
}

// Two walkers side by side, shoulder to shoulder (0.45 m apart), coming towards the only
// camera: their silhouettes are one blob from the first frame. Split at the heads
// (person_locator.h), they are two people from the start, each born though the other
// stands within birth_clear_mm. (Measured: MOTA 0.975; not split, 0.848, the second
// person born 20 frames late from what the first one's body leaves unexplained.)
TEST(MultiTracker, TwoWalkingTogetherAreTwo) {
  test::TempDir dir;
  const Camera front = LookAtCamera("cam0", 320, 240, 400, {7000, 1600, 0}, {0, 900, 0});
  const fs::path clip = Render({Walker("07_01", {true, 0, -225, 0, 0}, 0), Walker("35_10", {true, 0, 225, 0, 0}, 3)},
                               dir.path() / "together", 1, 0, {}, {front});
  const TrackJobResult r = RunTrackJob(Job(clip));
  Print("together", r);
  // Each started on their own half of the blob (TrackerOptions::split_merged_starts): 134
  // mm over bodytrack's 14 joints; started on the whole blob's place, 184.
  ExpectTwoPeople(r, 0.93, 160);
}

// At 10 frames/s (a surveillance camera's rate) a walker who enters once the others are
// tracked is born where they are by then: their birth looks back over 5-8 frames, in which
// they walked most of a metre. (Started where they were first seen, they were explained at
// IoU 0 and ended unconfirmed, again and again: on vtest.avi most walkers entering the
// plaza.)
TEST(MultiTracker, AWalkerEnteringAtTenFramesASecondIsBornWhereTheyAre) {
  test::TempDir dir;
  // The second walker's trial begins 0.9 s into the first's, after the start's frames; one
  // camera beside the walks sees them 70-100 px tall (a metre is 40-55 px there).
  const std::vector<ClipWalker> walkers = {Walker("07_04", {true, 0, -1250, 0, 0}, 0),
                                           Walker("07_01", {true, 0, 1250, 0, 0.35}, 3)};
  const fs::path clip =
      Render(walkers, dir.path() / "enters", 1, 0, [](ClipOptions* o) { o->fps = 10; }, {SideCamera(0, 8000)});
  const ClipGroundTruth truth = ReadGroundTruth(clip / "ground_truth.json");
  ASSERT_EQ(truth.people.size(), 2u);
  const ClipPerson& entering = truth.people[1];
  ASSERT_FALSE(entering.frames.empty());
  const int enters = entering.frames.front().frame;
  TrackJobOptions job = Job(clip);
  job.tracker.start_frames = 5;
  ASSERT_GT(enters, job.tracker.start_frames);
  const TrackJobResult r = RunTrackJob(job);
  Print("enters", r);
  // The frames from the entering walker's birth on, and how near them the person born is.
  int born_at = -1, near = 0, after = 0;
  for (const PeopleFrame& f : r.people) {
    if (f.index < enters) continue;
    const auto truth_frame = std::find_if(entering.frames.begin(), entering.frames.end(),
                                          [&](const ClipPersonFrame& t) { return t.frame == f.index; });
    if (truth_frame == entering.frames.end()) continue;
    const Eigen::Vector2d at(truth_frame->joints_mm(0, 0), truth_frame->joints_mm(2, 0));
    bool found = false;
    for (const PersonFrame& p : f.people)
      found = found || (p.frame.joints_mm.cols() > 0 &&
                        (Eigen::Vector2d(p.frame.joints_mm(0, 0), p.frame.joints_mm(2, 0)) - at).norm() < 300);
    if (found && born_at < 0) born_at = f.index;
    if (born_at >= 0) ++after, near += found;
  }
  std::printf("the second walker enters at frame %d of %zu, is tracked within 300 mm from frame %d, then in %d of %d "
              "frames\n",
              enters, r.people.size(), born_at, near, after);
  ASSERT_GE(born_at, 0);
  // Born after 5 of 8 frames and confirmed after 3 more, and tracked back into the frames
  // the birth saw them in (the lead-in, multi_tracker.h): measured 5 frames in, 10 without
  // the lead-in (MOTA 0.844 -> 0.922), 21 when started where they were first seen.
  EXPECT_LE(born_at, enters + 7);
  EXPECT_GE(near, 0.8 * after);
}

// One walker, with a shadow on the floor and clutter blobs moving over the masks: one
// person, nobody else ever born. (Measured MOTA 0.886: the first frames' shadow-stretched
// blobs place the walker differently in each camera, so the walker is confirmed at frame 9.)
TEST(MultiTracker, AShadowAndClutterStartNobody) {
  test::TempDir dir;
  const fs::path clip = Render({Walker("07_01", {}, 0)}, dir.path() / "shadow", 2, 0, [](ClipOptions* o) {
    o->scene.shadow = true;
    o->degradations.clutter_blobs = 3;
    o->seed = 4;
  });
  const TrackJobResult r = RunTrackJob(Job(clip));
  Print("shadow", r);
  EXPECT_EQ(Ids(r).size(), 1u);
  EXPECT_EQ(r.mot->false_positives, 0);
  EXPECT_GE(r.mot->mota, 0.8);
}

// Two walkers apart whose masks keep their shadows: the light is found (by whoever's
// tracker finds it first; here at frame 58 of 79, 2.7 degrees off) and is the clip's own;
// the walkers are tracked as well as without it (MOTA 0.861 either way: their births).
TEST(MultiTracker, TheWalkersShadowsLightIsFoundAndShared) {
  test::TempDir dir;
  ClipOptions options;
  const fs::path clip = Render({Walker("07_01", {true, 0, -1250, 0, 0}, 0), Walker("35_10", {true, 0, 1250, 0, 0}, 3)},
                               dir.path() / "shadows", 2, 0, [&](ClipOptions* o) {
                                 o->scene.shadow = true;
                                 o->seed = 3;
                                 options = *o;
                               });
  const ClipGroundTruth truth = ReadGroundTruth(clip / "ground_truth.json");
  const Eigen::Vector3d light =
      ClipScene(options.scene, truth.cameras, {truth.frames[0].joints_mm}, options.seed).light();
  const TrackJobResult r = RunTrackJob(Job(clip));
  TrackJobOptions without = Job(clip);
  without.tracker.shadow.enabled = false;
  const TrackJobResult bare = RunTrackJob(without);
  Print("shadows", r);
  Print("not drawn", bare);
  ExpectTwoPeople(r, 0.8, 130);
  EXPECT_GE(r.mot->mota, bare.mot->mota - 0.02);
  EXPECT_FALSE(bare.shadow_light_deg.has_value());
  ASSERT_TRUE(r.shadow_light_deg.has_value());
  const Eigen::Vector3d found = ShadowLight::Direction(r.shadow_light_deg->x(), r.shadow_light_deg->y());
  const double off_deg = std::acos(std::clamp(found.dot(light), -1.0, 1.0)) * 180 / std::numbers::pi;
  std::printf("the light found at frame %d, %.1f degrees off\n", r.shadow_light_frame, off_deg);
  EXPECT_LT(off_deg, 6);
}

// A walker who leaves the only camera's view (it sees the first half of the walk) ends,
// and nobody is reported after that: at 30 frames/s, and as soon (in seconds) at a
// surveillance camera's 10 (a person's end was 15 frames, 1.5 s of a body walking on
// there).
int LastInView(const ClipGroundTruth& truth) {
  const std::vector<std::vector<MotPoint>> in_view = TruePeople(truth, static_cast<int>(truth.frames.size()));
  int last = -1;
  for (size_t k = 0; k < in_view.size(); ++k)
    if (!in_view[k].empty()) last = static_cast<int>(k);
  return last;
}
int EndedAt(const TrackJobResult& r) {
  int ended_at = -1;
  for (const PeopleFrame& f : r.people)
    if (!f.ended.empty()) ended_at = f.index;
  return ended_at;
}
TEST(MultiTracker, AWalkerWhoLeavesEnds) {
  test::TempDir dir;
  for (const double fps : {30.0, 10.0}) {
    // At 10 frames/s the longer slow walk, so that the walker is out of view for long enough.
    const fs::path clip = Render({Walker(fps == 30 ? "07_01" : "07_04", {true, 1700, 0, 0, 0}, 0)},
                                 dir.path() / ("leaves" + std::to_string(static_cast<int>(fps))), 1, 0,
                                 [fps](ClipOptions* o) { o->fps = fps; }, {SideCamera(0, 3000)});
    const ClipGroundTruth truth = ReadGroundTruth(clip / "ground_truth.json");
    const int last_in_view = LastInView(truth);
    const TrackJobResult r = RunTrackJob(Job(clip));
    Print("leaves", r);
    const long bound = 2 * std::lround(MultiTrackerOptions().death_s * fps);  // frames
    ASSERT_LT(last_in_view + bound + 2, static_cast<int>(truth.frames.size())) << "the walker must leave for a while";
    const int ended_at = EndedAt(r);
    std::printf("%.0f frames/s: last in view at frame %d, ended at %d of %zu\n", fps, last_in_view, ended_at,
                truth.frames.size());
    EXPECT_GT(ended_at, last_in_view);
    EXPECT_LE(ended_at, last_in_view + bound);
    EXPECT_TRUE(r.people.back().people.empty());
    // Measured at 30 frames/s: 0.800 (2 frames before the walker is confirmed, 5 frames of
    // their body walking on out of view).
    if (fps == 30) {
      EXPECT_GE(r.mot->mota, 0.7);
    }
  }
}

// The clip's observed masks of its first `cameras` cameras as frames.
std::vector<Frame> ObservedFrames(const fs::path& clip, const ClipGroundTruth& truth, int cameras) {
  std::vector<Frame> frames;
  for (size_t k = 0; k < truth.frames.size(); ++k) {
    Frame frame;
    frame.index = static_cast<int>(k);
    frame.time_s = truth.frames[k].time_s;
    for (int c = 0; c < cameras; ++c) {
      const fs::path file = clip / "observed" / ("cam" + std::to_string(c)) / ClipFrameName(frame.index);
      frame.masks.push_back(cv::imread(file.string(), cv::IMREAD_GRAYSCALE));
      EXPECT_FALSE(frame.masks.back().empty()) << file;
    }
    frames.push_back(std::move(frame));
  }
  return frames;
}

// Several people tracked through `frames` as RunTrackJob tracks them (started on the first
// start_frames), each frame's people with the estimates from before confirmation placed.
std::vector<PeopleFrame> TrackPeople(const GaitModel& model, const std::vector<Camera>& cameras,
                                     const TrackJobOptions& job, const std::vector<Frame>& frames) {
  MultiTracker tracker(model, cameras, job.tracker, job.multi);
  tracker.Start({frames.begin(), frames.begin() + job.tracker.start_frames});
  std::vector<PeopleFrame> out;
  for (const Frame& f : frames) {
    out.push_back(tracker.Step(f));
    PlaceEarlier(&out);
  }
  return out;
}

// Two walkers apart through one camera at head height, their shins and below hidden in
// the first 16 frames (as behind a low wall): depth is read from where the feet are, so
// each birth is placed from the heads alone until the feet show. Each birth's first second
// is gone back over (TrackerOptions::start_backwards_s) from the later frames' surer
// place: the first second's estimates are nearer, and every later one is as without (the
// second pass leaves the trackers as they were).
TEST(MultiTracker, ABirthsFirstSecondIsGoneBackOver) {
  test::TempDir dir;
  const fs::path clip = Render({Walker("07_01", {true, -1200, -1500, 0, 0}, 0), Walker("35_10", {true, 1200, 1000, 0, 0}, 3)},
                               dir.path() / "apart", 1, 50, {}, {SideCamera(0, 8000)});
  const ClipGroundTruth truth = ReadGroundTruth(clip / "ground_truth.json");
  std::vector<Frame> frames = ObservedFrames(clip, truth, 1);
  for (size_t k = 0; k <= 15; ++k) {
    cv::Mat& mask = frames[k].masks[0];
    cv::Mat hidden = cv::Mat::zeros(mask.size(), CV_8UC1), labels, stats, centroids;
    const int n = cv::connectedComponentsWithStats(mask > 0, labels, stats, centroids);
    for (int b = 1; b < n; ++b) {
      if (stats.at<int>(b, cv::CC_STAT_AREA) < 100) continue;
      const int x = stats.at<int>(b, cv::CC_STAT_LEFT), y = stats.at<int>(b, cv::CC_STAT_TOP);
      const int w = stats.at<int>(b, cv::CC_STAT_WIDTH), h = stats.at<int>(b, cv::CC_STAT_HEIGHT);
      hidden(cv::Rect(x - 4, y + h * 3 / 4, w + 8, h / 4 + 4) & cv::Rect(0, 0, mask.cols, mask.rows)).setTo(255);
    }
    mask.setTo(0, hidden);
    frames[k].hidden.push_back(hidden);
  }
  const std::unique_ptr<GaitModel> model = ReadModelFile(Shared().model);
  const auto track = [&](double back_s) {
    TrackJobOptions job = Job(clip);
    job.tracker.start_backwards_s = back_s;
    return TrackPeople(*model, truth.cameras, job, frames);
  };
  const std::vector<PeopleFrame> forwards = track(0), back = track(1.0);
  ASSERT_EQ(forwards.size(), back.size());
  // Per estimate: the floor error against the nearer walker, in the track's first second
  // (from the person's first frame) or after it.
  double error[2][2] = {{0, 0}, {0, 0}};  // [run][after]
  int count[2][2] = {{0, 0}, {0, 0}};
  int same = 0, changed = 0;
  std::map<int, double> first_time;
  for (size_t k = 0; k < back.size(); ++k) {
    ASSERT_EQ(forwards[k].people.size(), back[k].people.size()) << "frame " << k;
    for (size_t i = 0; i < back[k].people.size(); ++i) {
      const PersonFrame* runs[2] = {&forwards[k].people[i], &back[k].people[i]};
      ASSERT_EQ(runs[0]->id, runs[1]->id);
      const bool after = back[k].time_s - first_time.emplace(runs[1]->id, back[k].time_s).first->second >= 1.0;
      const bool equal = runs[0]->frame.joints_mm.isApprox(runs[1]->frame.joints_mm, 0);
      if (after) {
        EXPECT_TRUE(equal) << "person " << runs[1]->id << " at frame " << k;
        same += equal;
      } else {
        changed += !equal;
      }
      for (int r = 0; r < 2; ++r) {
        if (runs[r]->frame.joints_mm.cols() == 0) continue;
        const Eigen::Vector2d at(runs[r]->frame.joints_mm(0, 0), runs[r]->frame.joints_mm(2, 0));
        double nearest = std::numeric_limits<double>::infinity();
        for (const ClipPerson& t : truth.people)
          for (const ClipPersonFrame& tf : t.frames)
            if (tf.frame == back[k].index)
              nearest = std::min(nearest, (Eigen::Vector2d(tf.joints_mm(0, 0), tf.joints_mm(2, 0)) - at).norm());
        if (std::isfinite(nearest)) error[r][after] += nearest, ++count[r][after];
      }
    }
  }
  for (int r = 0; r < 2; ++r)
    for (int a = 0; a < 2; ++a) error[r][a] /= std::max(1, count[r][a]);
  std::printf("floor error, first second of each track / after: forwards %.0f / %.0f mm, gone back over %.0f / %.0f mm "
              "(%d / %d estimates; %d changed)\n",
              error[0][0], error[0][1], error[1][0], error[1][1], count[1][0], count[1][1], changed);
  EXPECT_GE(same, 16);      // two people's last 10 frames, less a late confirmation
  EXPECT_GT(changed, 10);   // the second passes were kept
  // Measured (6 Dec): 90 mm forwards, 43 gone back over; after, 32 either way (3 Dec, with
  // the hidden pixels not yet kept apart as a painting: 112, 76 and 30).
  EXPECT_LT(error[1][0], 0.8 * error[0][0]);
}

// Two walkers apart through one camera at head height, and a wall painted (a static
// occluder, `--occluders`) behind both, its foot 30 rows above the farther one's, under
// their heads and shoulders all along. A painted object hides only who is behind it
// (tracker/filter/occluder_layers.h): every person's track is the one without the
// painting, frame by frame. Before the painting was kept apart from the others' drawings
// (Frame::painted) it hid both walkers' upper bodies, and a joint moved by up to 718 mm.
TEST(MultiTracker, AnObjectPaintedBehindTheWalkersChangesNothing) {
  test::TempDir dir;
  const fs::path clip = Render({Walker("07_01", {true, -1200, -1500, 0, 0}, 0), Walker("35_10", {true, 1200, 1000, 0, 0}, 3)},
                               dir.path() / "apart", 1, 40, {}, {SideCamera(0, 8000)});
  const ClipGroundTruth truth = ReadGroundTruth(clip / "ground_truth.json");
  const std::vector<Frame> frames = ObservedFrames(clip, truth, 1);
  cv::Rect walked;
  int farthest_feet = 240;  // the highest row any walker's feet reach
  for (const Frame& frame : frames) {
    cv::Mat labels, stats, centroids;
    const int n = cv::connectedComponentsWithStats(frame.masks[0] > 0, labels, stats, centroids);
    for (int b = 1; b < n; ++b) {
      if (stats.at<int>(b, cv::CC_STAT_AREA) < 100) continue;
      const cv::Rect blob(stats.at<int>(b, cv::CC_STAT_LEFT), stats.at<int>(b, cv::CC_STAT_TOP),
                          stats.at<int>(b, cv::CC_STAT_WIDTH), stats.at<int>(b, cv::CC_STAT_HEIGHT));
      walked |= blob;
      farthest_feet = std::min(farthest_feet, blob.y + blob.height);
    }
  }
  cv::Mat painting = cv::Mat::zeros(240, 320, CV_8UC1);
  painting(cv::Rect(walked.x, 0, walked.width, farthest_feet - 30)).setTo(255);
  int over = 0;  // frames with someone over the painting
  for (const Frame& f : frames) over += cv::countNonZero(painting & f.masks[0]) > 50;
  ASSERT_GT(over, 30) << "the painting must lie under someone";
  const std::unique_ptr<GaitModel> model = ReadModelFile(Shared().model);
  const auto track = [&](bool painted) {
    std::vector<Frame> seen = frames;
    if (painted)
      for (Frame& f : seen) f.hidden = {painting.clone()};
    return TrackPeople(*model, truth.cameras, Job(clip), seen);
  };
  const std::vector<PeopleFrame> plain = track(false), painted = track(true);
  ASSERT_EQ(plain.size(), painted.size());
  double most = 0;
  int estimates = 0;
  for (size_t k = 0; k < plain.size(); ++k) {
    ASSERT_EQ(plain[k].people.size(), painted[k].people.size()) << "frame " << k;
    for (size_t i = 0; i < plain[k].people.size(); ++i) {
      const TrackedFrame &a = plain[k].people[i].frame, &b = painted[k].people[i].frame;
      ASSERT_EQ(plain[k].people[i].id, painted[k].people[i].id);
      ASSERT_EQ(a.joints_mm.cols(), b.joints_mm.cols()) << "frame " << k;
      if (a.joints_mm.cols() == 0) continue;
      most = std::max(most, (a.joints_mm - b.joints_mm).cwiseAbs().maxCoeff());
      ++estimates;
    }
  }
  EXPECT_GT(estimates, 50);  // both walkers, most frames (57 measured)
  EXPECT_EQ(most, 0.0) << "the painting moved a joint by up to " << most << " mm";
}

// Paints a pillar over all of the walker's pixels in the first camera of `frames` (left
// out of its masks, as a pillar in front would leave them).
void PaintPillarInFirstCamera(std::vector<Frame>* frames) {
  cv::Rect path;  // the walker's pixels in the first camera, over the clip
  for (const Frame& f : *frames) path |= cv::boundingRect(f.masks[0]);
  const cv::Rect image(0, 0, (*frames)[0].masks[0].cols, (*frames)[0].masks[0].rows);
  cv::Mat pillar = cv::Mat::zeros(image.size(), CV_8UC1);
  pillar(cv::Rect(path.x - 6, path.y - 6, path.width + 12, path.height + 12) & image).setTo(255);
  for (Frame& f : *frames) {
    f.masks[0].setTo(0, pillar);
    f.hidden = {pillar, cv::Mat()};
  }
}

// The frames in which someone is reported within 500 mm of the walker on the floor.
std::vector<int> NearTheWalker(const ClipGroundTruth& truth, const std::vector<PeopleFrame>& out) {
  std::vector<int> near;
  for (size_t k = 0; k < out.size(); ++k) {
    const Eigen::Vector2d walker(truth.frames[k].joints_mm(0, 0), truth.frames[k].joints_mm(2, 0));
    for (const PersonFrame& p : out[k].people)
      if (p.frame.joints_mm.cols() > 0 &&
          (Eigen::Vector2d(p.frame.joints_mm(0, 0), p.frame.joints_mm(2, 0)) - walker).norm() < 500) {
        near.push_back(static_cast<int>(k));
        break;
      }
  }
  return near;
}

// One walker through two cameras, the first of which sees them wholly behind a painted
// pillar (PaintPillarInFirstCamera), the second's masks thinned by `thin_px` (0: as
// rendered): the frames in which they are tracked within 500 mm.
std::vector<int> TrackBehindAPillar(const fs::path& dir, int thin_px) {
  const fs::path clip = Render({Walker("07_01", {true, 0, 0, 0, 0}, 0)}, dir, 2, 40);
  const ClipGroundTruth truth = ReadGroundTruth(clip / "ground_truth.json");
  std::vector<Frame> frames = ObservedFrames(clip, truth, 2);
  PaintPillarInFirstCamera(&frames);
  if (thin_px > 0) {
    const cv::Mat square = cv::getStructuringElement(cv::MORPH_RECT, cv::Size(2 * thin_px + 1, 2 * thin_px + 1));
    for (Frame& f : frames) cv::erode(f.masks[1], f.masks[1], square);
  }
  const std::unique_ptr<GaitModel> model = ReadModelFile(Shared().model);
  return NearTheWalker(truth, TrackPeople(*model, truth.cameras, Job(clip), frames));
}

// The second camera's clear view starts the walker. Before, the first camera's empty
// pixels where a person would show there contradicted every sighting
// (MultiTracker::Contradicted), and nobody was ever born.
TEST(MultiTracker, AWalkerBehindAPaintedPillarInOneCameraIsBornFromTheOther) {
  test::TempDir dir;
  const std::vector<int> near = TrackBehindAPillar(dir.path() / "behind", 0);
  std::printf("the walker behind the pillar: tracked within 500 mm in %zu of 40 frames\n", near.size());
  EXPECT_GE(near.size(), 30u);
}

// The same with the second camera's masks thinned by 2 px (a segmentation that misses the
// body's edges): the fit explains them at an IoU near 0.5, and the first camera, where the
// estimate is drawn wholly behind the pillar, at 0. A camera in which the person stands
// behind a painted object has no say in their confirmation (MultiTracker::ConfirmIou), as
// it has none in their birth. Measured: within 500 mm in 40 of 40 frames; with the first
// camera's say, the walker was confirmed only at frame 20 (20 of 40).
TEST(MultiTracker, AWalkerBehindAPaintedPillarInOneCameraIsConfirmedByTheOther) {
  test::TempDir dir;
  const std::vector<int> near = TrackBehindAPillar(dir.path() / "thin", 2);
  std::printf("the thinly seen walker behind the pillar: tracked within 500 mm in %zu of 40 frames, the first %d\n",
              near.size(), near.empty() ? -1 : near[0]);
  EXPECT_GE(near.size(), 30u);
}

// One walker through one camera passing behind a painted pillar `width_mm` wide (their
// pixels under it left out of the masks, as a pillar in front would leave them).
struct PastAPillar {
  int hidden = 0;  // frames in which the walker is wholly behind the pillar
  size_t frames = 0, ids = 0, near = 0;  // frames, ids reported, frames within 500 mm
};
PastAPillar TrackPastAPillar(const fs::path& dir, double width_mm) {
  const Camera camera = SideCamera(0, 8000);
  const fs::path clip = Render({Walker("07_01", {true, 0, 0, 0, 0}, 0)}, dir, 1, 90, {}, {camera});
  const ClipGroundTruth truth = ReadGroundTruth(clip / "ground_truth.json");
  std::vector<Frame> frames = ObservedFrames(clip, truth, 1);
  Eigen::Vector2d left, right;
  PastAPillar past;
  const bool projected = camera.Project({-width_mm / 2, 0, 0}, &left) && camera.Project({width_mm / 2, 0, 0}, &right);
  EXPECT_TRUE(projected);
  if (!projected) return past;  // nothing tracked: the callers' expectations fail
  cv::Mat pillar = cv::Mat::zeros(frames[0].masks[0].size(), CV_8UC1);
  pillar.colRange(static_cast<int>(std::min(left.x(), right.x())), static_cast<int>(std::max(left.x(), right.x()))).setTo(255);
  for (Frame& f : frames) {
    past.hidden += cv::countNonZero(f.masks[0] & ~pillar) == 0;
    f.masks[0].setTo(0, pillar);
    f.hidden = {pillar};
  }
  const std::unique_ptr<GaitModel> model = ReadModelFile(Shared().model);
  const std::vector<PeopleFrame> out = TrackPeople(*model, truth.cameras, Job(clip), frames);
  std::set<int> ids;
  for (const PeopleFrame& f : out)
    for (const PersonFrame& p : f.people) ids.insert(p.id);
  past.frames = out.size();
  past.ids = ids.size();
  past.near = NearTheWalker(truth, out).size();
  std::printf("behind a pillar %.0f mm wide for %d frames of %zu: %zu ids, within 500 mm in %zu frames\n", width_mm,
              past.hidden, past.frames, past.ids, past.near);
  return past;
}

// Hidden wholly for most of a second behind a pillar 1.6 m wide, the walker keeps their id
// through it. A person behind a painted object is hidden as one behind another person is
// (MultiTracker::Behind), and kept predicted. Measured: hidden 19 frames of 79, one id,
// within 500 mm in 79 frames; before, they ended half a second after they were last seen
// and were born again with a new id when they came out (2 ids, 57 frames).
TEST(MultiTracker, AWalkerBehindAPaintedPillarKeepsTheirId) {
  test::TempDir dir;
  const PastAPillar past = TrackPastAPillar(dir.path() / "pillar", 1600);
  EXPECT_GT(past.hidden, 15);  // longer than death_s at 30 frames/s
  EXPECT_EQ(past.ids, 1u);
  EXPECT_GE(past.near, past.frames * 3 / 4);
}

// Behind a pillar 2 m wide (over a second), the prediction keeps up only walking on at the
// pace and the way the walker went (TrackerOptions::walk_on_as_seen, kBehindPainting for
// several people). Measured: hidden 34 frames of 79, one id, within 500 mm in 79 frames;
// without walking on, the prediction went on at half the walker's pace and they were born
// again when they came out (2 ids, 57 frames).
TEST(MultiTracker, AWalkerBehindAWidePaintedPillarWalksOnAndKeepsTheirId) {
  test::TempDir dir;
  const PastAPillar past = TrackPastAPillar(dir.path() / "wide", 2000);
  EXPECT_GT(past.hidden, 30);  // over a second at 30 frames/s
  EXPECT_EQ(past.ids, 1u);
  EXPECT_GE(past.near, past.frames * 3 / 4);
}

// One walker through one camera whose blob grows about its feet, frame by frame, to twice
// its height: they still stand where they did, so only a body ever taller explains them,
// and once it stands over max_stature_mm (2.2 m) for death_s it is nobody. Clutter drifting
// over the far side of a plaza was followed so, as a body 2.5 m tall 11 m away, until it
// left the view (the occluded overtaking clip: 53 frames of a false person; ended now
// after 37). Measured: over from frame 23, ended after frame 47 of 60; without the rule,
// reported to the last frame.
TEST(MultiTracker, SomeoneOnlyAGiantExplainsEnds) {
  test::TempDir dir;
  const fs::path clip = Render({Walker("07_01", {true, 0, 0, 0, 0}, 0)}, dir.path() / "growing", 1, 60);
  const ClipGroundTruth truth = ReadGroundTruth(clip / "ground_truth.json");
  std::vector<Frame> frames = ObservedFrames(clip, truth, 1);
  const int n = static_cast<int>(frames.size());
  const auto scale = [&](int k) { return 1.0 + k / (n - 1.0); };
  for (int k = 0; k < n; ++k) {
    cv::Mat& mask = frames[k].masks[0];
    const cv::Rect box = cv::boundingRect(mask);
    const cv::Point2f feet(box.x + 0.5f * box.width, static_cast<float>(box.y + box.height));
    cv::warpAffine(mask.clone(), mask, cv::getRotationMatrix2D(feet, 0, scale(k)), mask.size(), cv::INTER_NEAREST);
  }
  const std::unique_ptr<GaitModel> model = ReadModelFile(Shared().model);
  const TrackJobOptions job = Job(clip);
  const std::vector<PeopleFrame> out = TrackPeople(*model, truth.cameras, job, frames);
  // The frames the first person reported is in (later births, from the blob's lower
  // part, may follow).
  int first = -1, last = -1, id = 0;
  for (int k = 0; k < n; ++k)
    for (const PersonFrame& p : out[k].people)
      if (id == 0 || p.id == id) id = p.id, last = k, first = first < 0 ? k : first;
  // The first frame whose blob reads over max_stature_mm: the walker's height (the top of
  // the head over the floor, with their head's radius) times its scale.
  const double height = truth.frames[0].joints_mm.row(1).maxCoeff() + 88;
  int over = 0;
  while (over < n && height * scale(over) <= job.multi.max_stature_mm) ++over;
  std::printf("the growing walker (%.0f mm tall, read over %.0f mm from frame %d): person %d reported in frames %d-%d of %d\n",
              height, job.multi.max_stature_mm, over, id, first, last, n);
  ASSERT_GE(first, 0);
  ASSERT_GT(over, first);
  EXPECT_LT(last, n - 10);
}

std::string ReadBytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

TEST(MultiTracker, OneSeedGivesTheSamePosesWithAnyThreads) {
  test::TempDir dir;
  const fs::path clip = Render({Walker("07_01", {true, 0, 0, 0, 0}, 0), Walker("35_10", {true, 0, 0, 90, 0}, 3)},
                               dir.path() / "crossing", 2, 40);
  RunTrackJob(Job(clip, 1, dir.path() / "one"));
  RunTrackJob(Job(clip, 2, dir.path() / "two"));
  for (const char* file : {"poses.json", "tracked_1.bvh", "tracked_2.bvh"}) {
    const std::string a = ReadBytes(dir.path() / "one" / file), b = ReadBytes(dir.path() / "two" / file);
    ASSERT_GT(a.size(), 1000u) << file;
    EXPECT_TRUE(a == b) << file << " differs between 1 and 2 threads";
  }
}

TEST(MultiTracker, BadOptionsAreRefused) {
  MultiTrackerOptions o;
  std::string why;
  EXPECT_TRUE(o.Check(&why));
  o.birth_window = 2;  // under birth_frames
  EXPECT_FALSE(o.Check(&why));
  EXPECT_NE(why.find("birth"), std::string::npos);
  o = MultiTrackerOptions();
  o.max_people = 0;
  EXPECT_FALSE(o.Check(&why));
  o = MultiTrackerOptions();
  o.death_s = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(o.Check(&why));
  EXPECT_NE(why.find("death"), std::string::npos);
  o = MultiTrackerOptions();
  o.max_stature_mm = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(o.Check(&why));
  EXPECT_NE(why.find("stature"), std::string::npos);
}

}  // namespace
}  // namespace jgpm
