// The tracker end to end (RunTrackJob, as `jgpm track` runs it) on a clip whose truth is
// exact: a short two-camera clip of the unseen test subject (07_01) tracked from the masks
// alone with an ML-JGPM prior must come within a stated mean error of the true joints;
// the same masks shuffled in time must be tracked much worse (the masks, not the prior's
// idea of a walk, make the result); and one seed gives byte-identical results with one
// thread or two.
#include "tracker/filter/tracker.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <numbers>
#include <optional>
#include <random>
#include <sstream>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "io/base/text_reader.h"
#include "io/gait/gait_dataset.h"
#include "io/mocap/amc.h"
#include "io/mocap/asf.h"
#include "prior/model/model_file.h"
#include "prior/model/train.h"
#include "prior/prior_test_support.h"
#include "test_support.h"
#include "tracker/clip/clip_scene.h"
#include "tracker/clip/synthetic_clip.h"
#include "tracker/run/track_job.h"
#include "tracker/run/track_output.h"
#include "tracker/run/track_metrics.h"

namespace jgpm {
namespace {

namespace fs = std::filesystem;

constexpr int kFrames = 25;

// `frames` frames from the default two cameras at 160x120, no contact sheet.
ClipOptions SmallClip(int frames) {
  ClipOptions clip;
  clip.max_frames = frames;
  clip.rig.num_cameras = 2;
  clip.rig.width = 160;
  clip.rig.height = 120;
  clip.contact_sheet = false;
  return clip;
}

// The test subject's walk (07_01), read from the CMU data.
struct Walk0701 {
  ClipSource source = {(test::CmuRoot() / "subjects/07/07.asf").string(),
                       (test::CmuRoot() / "subjects/07/07_01.amc").string()};
  Skeleton skeleton = ReadAsf(source.asf);
  Motion motion = ReadAmc(source.amc, skeleton);
};

// An ML-JGPM torus prior from five training trials (subjects 02, 05, 35), a few full
// iterations (the table and the tracker take whatever the model is), and a 25-frame clip
// of the test subject from the default two cameras at 160x120. Made once per program.
struct Fixture {
  test::TempDir dir;
  fs::path model, clip;
  std::unique_ptr<GaitModel> loaded;  // the model file, read back
  ClipGroundTruth truth;              // the clip's
};
const Fixture& Shared() {
  static Fixture fixture;  // its folder is removed at exit
  static const bool made = [] {
    Fixture* f = &fixture;
    const auto model = test::TrainOnFirstWalks(ModelKind::kMljgpmTorus, 5, 5);
    f->model = f->dir.path() / "mljgpm.json";
    WriteModelFile(f->model, *model);

    const Walk0701 walk;
    f->clip = f->dir.path() / "clip";
    RenderClip(walk.skeleton, walk.motion, walk.source, {}, SmallClip(kFrames), f->clip.string());
    f->loaded = ReadModelFile(f->model);
    f->truth = ReadGroundTruth(f->clip / "ground_truth.json");
    return true;
  }();
  (void)made;
  return fixture;
}

// A tracker on the shared model and `cameras` (default: the shared clip's): `particles`
// per layer, `seed`.
std::unique_ptr<Tracker> SharedTracker(int particles, uint64_t seed = 1, const std::vector<Camera>* cameras = nullptr) {
  const Fixture& f = Shared();
  TrackerOptions options;
  options.annealing.particles = particles;
  options.annealing.seed = seed;
  return std::make_unique<Tracker>(*f.loaded, cameras ? *cameras : f.truth.cameras, options);
}

// A small budget: 2 cameras at 160x120, 150 particles x 4 layers.
TrackJobOptions Job(const fs::path& clip, int threads, const fs::path& out = {}) {
  TrackJobOptions job;
  job.model = Shared().model.string();
  job.source.clip = clip.string();
  job.out = out.string();
  job.overlays = false;
  job.tracker.threads = threads;
  job.tracker.annealing.particles = 150;
  job.tracker.annealing.layers = 4;
  job.tracker.annealing.seed = 7;
  return job;
}

std::string ReadBytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// The clip with each camera's observed masks permuted in time (one permutation for all
// cameras, so the views still agree with each other but not with the truth or the walk).
fs::path ShuffledCopy(const fs::path& clip, const fs::path& to) {
  fs::copy(clip, to, fs::copy_options::recursive);
  std::vector<int> order(kFrames);
  for (int k = 0; k < kFrames; ++k) order[k] = k;
  std::mt19937 rng(3);
  std::shuffle(order.begin(), order.end(), rng);
  for (const auto& entry : fs::directory_iterator(clip / "observed")) {
    const fs::path camera = entry.path().filename();
    for (int k = 0; k < kFrames; ++k) {
      const std::string name = ClipFrameName(k), source = ClipFrameName(order[k]);
      fs::copy_file(clip / "observed" / camera / source, to / "observed" / camera / name,
                    fs::copy_options::overwrite_existing);
    }
  }
  return to;
}

// Mean horizontal distance (mm) of the tracked root from the true one.
double RootError(const TrackRun& run, const ClipGroundTruth& truth) {
  double sum = 0;
  for (const TrackedFrame& f : run.frames) {
    const Eigen::Vector3d d = f.joints_mm.col(0) - truth.frames[f.index].joints_mm.col(0);  // bone 0: the root
    sum += std::hypot(d.x(), d.z()) / run.frames.size();
  }
  return sum;
}

void Print(const char* what, const TrackJobResult& r, const ClipGroundTruth& truth) {
  const TrackErrors& e = r.errors->bodytrack14;
  std::printf("%-9s %6.1f mm absolute, %6.1f root-relative, %6.1f Procrustes, legs swapped in %2.0f%% of frames, "
              "root %5.1f mm off, %.2f s\n",
              what, e.absolute_mm, e.root_relative_mm, e.procrustes_mm, 100 * e.swap_rate, RootError(r.run, truth),
              r.run.tracking_seconds);
}

// Bounds, from the masks alone: measured 80 mm with this seed (76-84 mm over seeds 3-7):
// the pose is right (30-45 mm per frame) except while the legs are swapped, which
// silhouettes barely tell apart (tracker/filter/tracker.h): this clip starts with them swapped
// and the tracker turns them round after 7-9 of its 25 frames. The root is placed within
// 28-32 mm. From the truth (`--init truth`): 44 mm (37-50 over seeds 3-7, never swapped).
// Shuffled in time the masks put the walker 400 mm from where the truth is: measured
// 526 mm (512-534 over seeds).
constexpr double kAutoBoundMm = 130, kTruthStartBoundMm = 70, kRootBoundMm = 60;

TEST(Tracker, TracksAWalkAndNotItsShuffledMasks) {
  const Fixture& f = Shared();
  const ClipGroundTruth& truth = f.truth;
  const TrackJobResult result = RunTrackJob(Job(f.clip, 2));
  ASSERT_EQ(static_cast<int>(result.run.frames.size()), kFrames);
  ASSERT_TRUE(result.errors.has_value());
  Print("clip:", result, truth);
  int tracked = 0;
  for (const TrackedFrame& frame : result.run.frames) tracked += frame.status == TrackStatus::kTracked;
  EXPECT_EQ(tracked, kFrames);
  const TrackErrors& e = result.errors->bodytrack14;
  EXPECT_EQ(e.frames, kFrames);
  EXPECT_LT(e.absolute_mm, kAutoBoundMm);
  EXPECT_LT(RootError(result.run, truth), kRootBoundMm);

  TrackJobOptions from_truth = Job(f.clip, 2);
  from_truth.truth_start = true;
  const TrackJobResult started = RunTrackJob(from_truth);
  ASSERT_TRUE(started.errors.has_value());
  Print("truth:", started, truth);
  EXPECT_LT(started.errors->bodytrack14.absolute_mm, kTruthStartBoundMm);
  EXPECT_LT(RootError(started.run, truth), kRootBoundMm);

  test::TempDir scratch;
  const fs::path shuffled = ShuffledCopy(f.clip, scratch.path() / "shuffled");
  const TrackJobResult bad = RunTrackJob(Job(shuffled, 2));
  ASSERT_TRUE(bad.errors.has_value());
  Print("shuffled:", bad, truth);
  EXPECT_GT(bad.errors->bodytrack14.absolute_mm, 1.5 * e.absolute_mm);
  EXPECT_GT(bad.errors->bodytrack14.absolute_mm, 300);
}

// The posture offset as a per-person state (--adapt posture, off by default: measured no
// better on the suite) tracks the walk within the same bound, and does change the result.
TEST(Tracker, TracksAWalkWithPostureAdaptation) {
  const Fixture& f = Shared();
  const ClipGroundTruth& truth = f.truth;
  TrackJobOptions job = Job(f.clip, 2);
  job.tracker.refinement.adapt_posture = true;
  const TrackJobResult adapted = RunTrackJob(job);
  ASSERT_TRUE(adapted.errors.has_value());
  Print("posture:", adapted, truth);
  EXPECT_LT(adapted.errors->bodytrack14.absolute_mm, kAutoBoundMm);
  EXPECT_LT(RootError(adapted.run, truth), kRootBoundMm);
  const TrackJobResult plain = RunTrackJob(Job(f.clip, 2));
  EXPECT_NE(adapted.errors->bodytrack14.absolute_mm, plain.errors->bodytrack14.absolute_mm);
}

// Every likelihood evaluation is counted: without the refinement, a tracked frame costs
// particles x layers and the two scores of the mirror test; the first frame weighs
// start_particle_factor times the particles in its first layer, then the usual number in
// each of its other start_layers - 1 layers.
TEST(Tracker, CountsEveryEvaluation) {
  const Fixture& f = Shared();
  TrackJobOptions job = Job(f.clip, 2);
  job.tracker.refinement.enabled = false;
  job.source.max_frames = 6;
  const TrackJobResult result = RunTrackJob(job);
  const AnnealingOptions& a = job.tracker.annealing;
  ASSERT_EQ(result.run.frames.size(), 6u);
  for (const TrackedFrame& frame : result.run.frames) {
    if (frame.status != TrackStatus::kTracked) continue;
    // The annealing's, the estimate against its mirror (2) and, after the first, the
    // estimate judged before its update is kept (predict_bad_frames, 1).
    const int expected = frame.index == 0 ? a.particles * (job.tracker.start_particle_factor + job.tracker.start_layers - 1) + 2
                                          : a.particles * a.layers + 3;
    EXPECT_EQ(frame.evaluations, expected) << "frame " << frame.index;
  }
}

// A start's frames are given once the tracker has read on (StartBackOver): the progress
// counts the frames read, not the frame given, or its rate ran ahead of the truth (101
// frames/s shown on a clip tracked at 22).
TEST(Tracker, ProgressCountsTheFramesRead) {
  const Fixture& f = Shared();
  TrackJobOptions job = Job(f.clip, 2);
  job.tracker.refinement.enabled = false;
  job.source.max_frames = 12;
  std::vector<std::pair<int, int>> reports;  // (frame given, frames read)
  RunTrackJob(job, [&reports](const TrackedFrame& frame, int read, int total, int) {
    EXPECT_EQ(total, 12);
    reports.emplace_back(frame.index, read);
  });
  ASSERT_EQ(reports.size(), 12u);
  EXPECT_EQ(reports.front().first, 0);
  EXPECT_EQ(reports.front().second, 12);  // held for the start until the clip ended
  for (size_t k = 1; k < reports.size(); ++k) {
    EXPECT_EQ(reports[k].first, reports[k - 1].first + 1);
    EXPECT_GE(reports[k].second, reports[k - 1].second);
    EXPECT_GT(reports[k].second, reports[k].first);
  }
}

TEST(Tracker, OneSeedGivesTheSameResultWithAnyThreads) {
  const Fixture& f = Shared();
  test::TempDir out;
  RunTrackJob(Job(f.clip, 1, out.path() / "one"));
  RunTrackJob(Job(f.clip, 2, out.path() / "two"));
  for (const char* file : {"poses.json", "tracked.bvh", "tracked.amc"}) {
    const std::string a = ReadBytes(out.path() / "one" / file), b = ReadBytes(out.path() / "two" / file);
    ASSERT_GT(a.size(), 1000u) << file;
    EXPECT_TRUE(a == b) << file << " differs between 1 and 2 threads";
  }
  // And the seed matters: another one gives another track.
  TrackJobOptions other = Job(f.clip, 2, out.path() / "other");
  other.tracker.annealing.seed = 8;
  RunTrackJob(other);
  EXPECT_NE(ReadBytes(out.path() / "one" / "poses.json"), ReadBytes(out.path() / "other" / "poses.json"));
}

// The clip's frame k with its observed masks, as a frame source gives it.
Frame ClipFrameAt(const ClipGroundTruth& truth, const fs::path& clip, int k) {
  Frame frame;
  frame.index = k;
  frame.time_s = truth.frames[k].time_s;
  for (const Camera& c : truth.cameras) {
    frame.masks.push_back(cv::imread((clip / "observed" / c.name / ClipFrameName(k)).string(), cv::IMREAD_GRAYSCALE));
  }
  return frame;
}

// A restart draws its own particles (every start used to draw from frame 0's random
// numbers, so a tracker restarting in the same place made the same guesses again).
TEST(Tracker, EachStartDrawsItsOwnParticles) {
  const Fixture& f = Shared();
  const auto a = SharedTracker(50), b = SharedTracker(50);
  const Frame frame = ClipFrameAt(f.truth, f.clip, 5);
  Frame later = frame;
  later.index = 9;
  ASSERT_TRUE(a->StartFromFrames({frame}));
  ASSERT_TRUE(b->StartFromFrames({frame}));
  EXPECT_EQ(a->filter().particles(), b->filter().particles());  // same frame, same seed: same draws
  ASSERT_TRUE(b->StartFromFrames({later}));
  EXPECT_NE(a->filter().particles(), b->filter().particles());
}

// The mean IoU counts the cameras that see someone where the person is expected or draw
// the estimate: one that does neither is no evidence (it averaged in an IoU of 0, and two
// cameras with one out of view restarted every 5 frames). Hand-computed.
TEST(TrackedFrame, MeanIouLeavesOutCamerasWithNoEvidence) {
  TrackedFrame f;
  CameraScore seen, away;
  seen.model_px = 100;
  seen.observed_px = 100;
  seen.overlap_px = 80;  // IoU 80 / 120
  f.cameras = {seen, away};
  EXPECT_NEAR(f.MeanIou(), 80.0 / 120, 1e-12);
  away.observed_px = 50;  // someone seen there, nothing drawn: evidence, IoU 0
  f.cameras = {seen, away};
  EXPECT_NEAR(f.MeanIou(), 0.5 * 80.0 / 120, 1e-12);
  f.cameras = {CameraScore(), CameraScore()};
  EXPECT_EQ(f.MeanIou(), 1.0);  // nobody anywhere, nothing drawn: nothing wrong
}

// The second pass over a start is kept unless its frames explain the masks worse, by mean
// IoU, than the first's by more than the margin (hand-made scores: IoU 0.8 and 0.75).
TEST(StartBackOver, KeepsTheSecondPassUnlessItExplainsWorse) {
  const auto frame = [](int overlap) {
    TrackedFrame f;
    CameraScore c;
    c.model_px = c.observed_px = 90;
    c.overlap_px = overlap;  // IoU overlap / (180 - overlap)
    f.cameras = {c};
    return f;
  };
  const std::vector<TrackedFrame> good(3, frame(80)), worse(3, frame(77)), mixed = {frame(80), frame(80), frame(77)};
  ASSERT_NEAR(good[0].MeanIou(), 0.8, 1e-12);
  ASSERT_NEAR(worse[0].MeanIou(), 77.0 / 103, 1e-12);  // 0.0524 lower
  EXPECT_TRUE(StartBackOver::KeepSecond(good, good, 0));
  EXPECT_TRUE(StartBackOver::KeepSecond(worse, good, 0));
  EXPECT_FALSE(StartBackOver::KeepSecond(good, worse, 0.02));
  EXPECT_TRUE(StartBackOver::KeepSecond(good, worse, 0.06));
  EXPECT_TRUE(StartBackOver::KeepSecond(good, mixed, 0.02));   // 0.0175 lower on the mean
  EXPECT_FALSE(StartBackOver::KeepSecond(good, mixed, 0.015));
  EXPECT_FALSE(StartBackOver::KeepSecond({}, {}, 1));
  EXPECT_FALSE(StartBackOver::KeepSecond(good, std::vector<TrackedFrame>{good[0]}, 1));
  // Drawn nowhere and seeing nobody (behind a pillar) is neither a fit nor a loss: it
  // counts the unseen IoU (0.2), not MeanIou's 1. Not better than 0.8 on the walker; better
  // than 0.1 predicted beside the pillar.
  TrackedFrame hidden;
  hidden.cameras = {CameraScore()};
  ASSERT_EQ(hidden.MeanIou(), 1.0);
  const std::vector<TrackedFrame> behind(3, hidden), beside(3, frame(18)), partly = {good[0], hidden, hidden};
  ASSERT_NEAR(beside[0].MeanIou(), 18.0 / 162, 1e-12);
  EXPECT_FALSE(StartBackOver::KeepSecond(good, behind, 0.02, 0.2));
  EXPECT_TRUE(StartBackOver::KeepSecond(behind, good, 0.02, 0.2));
  EXPECT_TRUE(StartBackOver::KeepSecond(beside, behind, 0.02, 0.2));
  EXPECT_FALSE(StartBackOver::KeepSecond(behind, beside, 0.02, 0.2));
  EXPECT_TRUE(StartBackOver::KeepSecond(behind, behind, 0, 0.2));
  EXPECT_FALSE(StartBackOver::KeepSecond(good, partly, 0.3, 0.2));  // (0.8 + 0.4) / 3 a frame: 0.4 lower
  EXPECT_TRUE(StartBackOver::KeepSecond(good, partly, 0.41, 0.2));
}

// A start's frames wait for its leg order to settle (the other order's trial decided),
// and go back from there when the order may have changed after the first pass went back:
// a pass from before carries the other order back (a coat clip's seed 1, 4 cameras: legs
// swapped for 25 frames, 87 -> 52 mm). Here the first pass goes back at frame 3, inside
// the start's search of the other order (mirror_frames 6), so the order may change after
// it: every frame held must cost a second pass from the settled frame, not only those
// before frame 3. Without the wait, frames were given at frame 3.
// Half a cycle on swaps the legs: an estimate more than a quarter cycle off the last one
// walked on (its cadence for the time between) has the other order, across the cycle's
// wrap as well.
TEST(Tracker, AnEstimateAQuarterCycleOffHasTheOtherLegOrder) {
  const Eigen::Vector2d last(0.9, 1.2);  // 1.2 cycles/s: 0.04 a frame at 30 frames/s
  const double dt = 0.1;                 // walked on to 0.02 (1.02)
  EXPECT_FALSE(OtherLegOrder(0.02, last, dt));
  EXPECT_FALSE(OtherLegOrder(0.26, last, dt));  // 0.24 on
  EXPECT_TRUE(OtherLegOrder(0.28, last, dt));   // 0.26 on
  EXPECT_FALSE(OtherLegOrder(0.79, last, dt));  // 0.23 back, across the wrap
  EXPECT_TRUE(OtherLegOrder(0.76, last, dt));   // 0.26 back
  EXPECT_TRUE(OtherLegOrder(0.52, last, dt));   // half a cycle: swapped
  EXPECT_FALSE(OtherLegOrder(0.9, Eigen::Vector2d(0.9, -1.2), 0));  // no time, no walk
  EXPECT_TRUE(OtherLegOrder(0.9, Eigen::Vector2d(0.9, -1.2), 0.25));  // walking backwards: 0.3 back
}

// The other order's trial compares two orders: its second tracker holds the order it
// began in, although its particles are copied from the first's, which hold both after a
// start's search, and the masks (legs joined, as by a skirt) do not choose. Without the
// hold, seed 3's second tracker went back to the first's order during its trial. And it
// searches with all the first's annealing layers.
TEST(Tracker, TheOtherLegOrdersTrialHoldsItsOrder) {
  const Fixture& f = Shared();
  TrackerOptions options;
  options.annealing.particles = 100;
  options.annealing.seed = 3;
  options.mirror_every = 2;
  options.mirror_frames = 4;
  options.mirror_margin = 1e9;
  options.legs_trial_frames = 12;
  options.legs_trial_margin = 1e9;  // the trial never wins: it runs its course
  Tracker tracker(*f.loaded, f.truth.cameras, options);
  tracker.StartAt(TruthGuess(f.truth, *f.loaded, tracker.state_model()));  // the right order
  const int rate = tracker.state_model().placement().rate;
  int trial_frames = 0;
  std::optional<Eigen::VectorXd> last;
  double last_time_s = 0;
  for (int k = 0; k < kFrames; ++k) {
    Frame frame = ClipFrameAt(f.truth, f.clip, k);
    // The gap between the legs filled (a skirt): either order explains the masks.
    for (cv::Mat& m : frame.masks)
      cv::morphologyEx(m, m, cv::MORPH_CLOSE, cv::getStructuringElement(cv::MORPH_RECT, {31, 1}));
    tracker.Step(frame);
    const Tracker* trial = tracker.legs_trial();
    if (!trial) {
      last.reset();
      continue;
    }
    // As hard a search as the first's: with half the layers it fitted worse than a coat's
    // two orders differ, and lost trials the right order should have won.
    EXPECT_EQ(trial->options().annealing.layers, options.annealing.layers);
    const Eigen::VectorXd estimate = trial->filter().Mean();
    if (last) {
      ++trial_frames;
      EXPECT_FALSE(OtherLegOrder(estimate[0], {(*last)[0], (*last)[rate]}, frame.time_s - last_time_s))
          << "frame " << k << ": the trial turned its legs";
    }
    last = estimate;
    last_time_s = frame.time_s;
  }
  EXPECT_GE(trial_frames, 8);
}

TEST(StartBackOver, GoesBackFromWhereTheLegOrderIsSettled) {
  const Fixture& f = Shared();
  TrackerOptions options;
  options.annealing.particles = 60;
  options.start_backwards_s = 0.1;  // 3 frames at 30 frames/s
  options.mirror_frames = 6;
  options.legs_trial_frames = 4;
  Tracker tracker(*f.loaded, f.truth.cameras, options);
  std::vector<Frame> frames;
  for (int k = 0; k < kFrames; ++k) frames.push_back(ClipFrameAt(f.truth, f.clip, k));
  ASSERT_TRUE(tracker.StartFromFrames({frames.begin(), frames.begin() + options.start_frames}));
  StartBackOver hold(&tracker);
  std::vector<StartBackOver::Estimate> ready;
  std::vector<int> forward_evaluations;
  int given_at = -1;
  for (int k = 0; k < kFrames && given_at < 0; ++k) {
    TrackedFrame estimate = tracker.Step(frames[k]);
    ASSERT_EQ(estimate.status, TrackStatus::kTracked) << "frame " << k;
    forward_evaluations.push_back(estimate.evaluations);
    hold.Add(frames[k], std::move(estimate), &ready);
    if (!ready.empty()) given_at = k;
    else EXPECT_FALSE(tracker.LegsSettled() && frames[k].time_s >= options.start_backwards_s) << "frame " << k;
  }
  ASSERT_GE(given_at, options.mirror_frames + options.legs_trial_frames - 1);
  EXPECT_TRUE(tracker.LegsSettled());
  ASSERT_EQ(static_cast<int>(ready.size()), given_at + 1);
  for (int k = 0; k < given_at; ++k) {
    EXPECT_EQ(ready[k].frame.index, k);
    EXPECT_GT(ready[k].estimate.evaluations, forward_evaluations[k]) << "frame " << k << " not gone back over";
  }
  EXPECT_EQ(ready[given_at].estimate.evaluations, forward_evaluations[given_at]);  // where it went back from

  // Frames that end while the legs settle are given gone back over as far as it went: at
  // frame 3, before the first 3 (it was left out once it waited).
  Tracker again(*f.loaded, f.truth.cameras, options);
  ASSERT_TRUE(again.StartFromFrames({frames.begin(), frames.begin() + options.start_frames}));
  StartBackOver short_hold(&again);
  std::vector<StartBackOver::Estimate> given;
  for (int k = 0; k <= 4; ++k) {
    short_hold.Add(frames[k], again.Step(frames[k]), &given);
    ASSERT_TRUE(given.empty()) << "frame " << k;
  }
  ASSERT_FALSE(again.LegsSettled());
  short_hold.Flush(&given);
  ASSERT_EQ(given.size(), 5u);
  for (int k = 0; k < 3; ++k) EXPECT_GT(given[k].estimate.evaluations, forward_evaluations[k]) << "frame " << k;
  for (int k = 3; k <= 4; ++k) EXPECT_EQ(given[k].estimate.evaluations, forward_evaluations[k]) << "frame " << k;
}

// Masks of a segmentation's specks only (the person gone): nobody is in view at once, not
// after five frames of tracking specks (every mask was "someone" while any pixel was set).
TEST(Tracker, SpecksAreNobody) {
  const Fixture& f = Shared();
  const auto tracker = SharedTracker(60);
  ASSERT_TRUE(tracker->StartFromFrames({ClipFrameAt(f.truth, f.clip, 0)}));
  for (int k = 0; k < 6; ++k) EXPECT_EQ(tracker->Step(ClipFrameAt(f.truth, f.clip, k)).status, TrackStatus::kTracked) << k;
  Frame specks = ClipFrameAt(f.truth, f.clip, 6);
  std::mt19937 rng(4);
  for (cv::Mat& mask : specks.masks) {
    mask.setTo(0);
    for (int s = 0; s < 12; ++s) mask.at<uint8_t>(rng() % mask.rows, rng() % mask.cols) = 255;
  }
  EXPECT_EQ(tracker->Step(specks).status, TrackStatus::kLost);
}

// The mask moved `px` pixels to the right (what leaves the image is dropped).
cv::Mat ShiftedRight(const cv::Mat& mask, int px) {
  cv::Mat moved = cv::Mat::zeros(mask.size(), mask.type());
  mask(cv::Rect(0, 0, mask.cols - px, mask.rows)).copyTo(moved(cv::Rect(px, 0, mask.cols - px, mask.rows)));
  return moved;
}

// Someone in front of the walker from row `top` of their blob down: the mask loses their
// blob's box from there, grown by 4 px (as another's drawing would cover it), and the
// hidden pixels are returned (Frame::hidden).
cv::Mat HideFrom(cv::Mat* mask, int top) {
  const cv::Rect box = cv::boundingRect(*mask);
  const cv::Rect front =
      cv::Rect(box.x - 4, top, box.width + 8, box.y + box.height + 4 - top) & cv::Rect(0, 0, mask->cols, mask->rows);
  cv::Mat hidden = cv::Mat::zeros(mask->size(), CV_8UC1);
  hidden(front).setTo(255);
  mask->setTo(0, hidden);
  return hidden;
}

// The walker hidden for half a second while a walker-sized blob shows up a metre and more
// away in both views: the person is predicted, not restarted on the blob, and tracked
// again where they reappear. Over several seeds: the four frames before the person counts
// as hidden, fitted to the blob aside, shrank the body and its stride, and the prediction
// then walked on at a fifth of the walker's speed, 1.3 m behind by the end for seeds 4 and 6
// (TrackerOptions::predict_bad_frames).
TEST(Tracker, AHiddenPersonIsPredictedNotSwappedForSomeoneElsewhere) {
  const Fixture& f = Shared();
  const ClipGroundTruth& truth = f.truth;
  for (uint64_t seed = 1; seed <= 6; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    const auto tracker = SharedTracker(100, seed);
    std::vector<Frame> first;
    for (int k = 0; k < 5; ++k) first.push_back(ClipFrameAt(truth, f.clip, k));
    ASSERT_TRUE(tracker->StartFromFrames(first));
    std::vector<TrackStatus> statuses;
    std::vector<double> root_error;
    for (int k = 0; k < kFrames; ++k) {
      Frame frame = ClipFrameAt(truth, f.clip, k);
      if (k >= 8 && k < 22) {
        for (cv::Mat& mask : frame.masks) {  // the walker's own silhouette, 55 px aside
          mask = ShiftedRight(mask, 55);
        }
      }
      const TrackedFrame out = tracker->Step(frame);
      statuses.push_back(out.status);
      const Eigen::Vector3d d = out.state.size()
                                    ? Eigen::Vector3d(out.joints_mm.col(0) - truth.frames[k].joints_mm.col(0))
                                    : Eigen::Vector3d::Constant(1e9);
      root_error.push_back(std::hypot(d.x(), d.z()));
    }
    std::string line;
    for (TrackStatus s : statuses) line += TrackStatusName(s)[0];
    std::printf("seed %d: statuses %s; root error while hidden (frames 8-21): max %.0f mm\n", static_cast<int>(seed),
                line.c_str(), *std::max_element(root_error.begin() + 8, root_error.begin() + 22));
    for (int k = 8; k < 22; ++k) {
      EXPECT_NE(statuses[k], TrackStatus::kLost) << k;
      EXPECT_LT(root_error[k], 600) << k;  // never on the blob (well over a metre away)
    }
    EXPECT_EQ(statuses[20], TrackStatus::kPredicted);
    EXPECT_EQ(statuses[kFrames - 1], TrackStatus::kTracked);
    EXPECT_LT(root_error[kFrames - 1], 150);
  }
}

// Someone tracked with the walker (several people at once) passes in front of them in
// both views for frames 8-15, covering all of them but their head: the masks
// lose those pixels and the frames mark them hidden, as MultiTracker::Step does. The
// walker is predicted through it, not lost (the poor fit and a mask with nobody
// person-sized left were read as nobody there, the track dropped at once and the person
// ended, in the 5-walker plaza clip). Without the hidden pixels (nobody known in front),
// or with the masks empty and the others in front of their legs only (the walker left:
// nobody on the floor where their upper body would show), the same frames lose them.
// And when the others have gone from in front of the prediction (frames 12-15 of the
// last case) while the walker shows 55 px aside (a metre and more from the prediction),
// they are looked for again as after a loss and tracked there, not kept predicted behind
// nobody. Wholly behind a taller person whose drawing ends 3 rows below the walker's
// crown, the mask empty: predicted too (the sliver of the walker's drawing above the
// others' on empty floor is not "gone"; the 5-walker plaza clip lost a walker so when
// their rule asked a third of the drawing's rest, 14 of 610 px, to be on foreground).
TEST(Tracker, APersonBehindOthersTrackedWithThemIsPredictedNotLost) {
  const Fixture& f = Shared();
  enum class Case { kBehind, kUnknown, kGone, kOthersGone, kWhollyBehind };
  const auto statuses = [&](Case what) {
    const auto tracker = SharedTracker(100, 3);
    std::vector<Frame> first;
    for (int k = 0; k < 5; ++k) first.push_back(ClipFrameAt(f.truth, f.clip, k));
    EXPECT_TRUE(tracker->StartFromFrames(first));
    std::string line;
    for (int k = 0; k < 16; ++k) {
      Frame frame = ClipFrameAt(f.truth, f.clip, k);
      if (what == Case::kOthersGone && k >= 12) {
        for (cv::Mat& mask : frame.masks) {  // nobody in front; the walker 55 px aside
          mask = ShiftedRight(mask, 55);
          frame.hidden.push_back(cv::Mat::zeros(mask.size(), CV_8UC1));
        }
      } else if (k >= 8) {
        for (cv::Mat& mask : frame.masks) {
          const cv::Rect box = cv::boundingRect(mask);
          // Below the head (below the hips when gone, the crown when wholly).
          const int top = what == Case::kWhollyBehind ? box.y + 3 : box.y + box.height / (what == Case::kGone ? 2 : 6);
          const cv::Mat hidden = HideFrom(&mask, top);
          if (what == Case::kGone || what == Case::kWhollyBehind) mask.setTo(0);
          if (what != Case::kUnknown) frame.hidden.push_back(hidden);
        }
      }
      const TrackedFrame out = tracker->Step(frame);
      line += TrackStatusName(out.status)[0];
      if (k == 15 && what == Case::kOthersGone) {
        // Where the walker shows now: the truth's root seen 55 px aside in each camera, which
        // is no one place; the start tries where the two cameras' lines of sight meet
        // (Tracker::Guess) and fits both within 20 px (14 and 4; from camera 0's reading
        // alone, 3 and 54).
        for (const Camera& camera : f.truth.cameras) {
          Eigen::Vector2d at, drawn(1e9, 0);
          EXPECT_TRUE(camera.Project(f.truth.frames[k].joints_mm.col(0), &at));
          at.x() += 55;
          if (out.state.size()) camera.Project(out.joints_mm.col(0), &drawn);
          std::printf("others gone: the root drawn %.0f px from where the walker shows\n", (drawn - at).norm());
          EXPECT_LT((drawn - at).norm(), 20);
        }
      }
    }
    return line;
  };
  const std::string behind = statuses(Case::kBehind), unknown = statuses(Case::kUnknown),
                    gone = statuses(Case::kGone), others_gone = statuses(Case::kOthersGone),
                    wholly = statuses(Case::kWhollyBehind);
  std::printf("frames 0-15: behind others %s, nobody known in front %s, gone %s, others gone at 12 %s, "
              "wholly behind %s\n",
              behind.c_str(), unknown.c_str(), gone.c_str(), others_gone.c_str(), wholly.c_str());
  EXPECT_EQ(behind.substr(0, 8), std::string(8, 't'));
  EXPECT_EQ(behind.substr(8).find('l'), std::string::npos) << behind;
  EXPECT_EQ(wholly.substr(8).find('l'), std::string::npos) << wholly;
  EXPECT_NE(unknown.substr(8).find('l'), std::string::npos) << unknown;
  EXPECT_NE(gone.substr(8).find('l'), std::string::npos) << gone;
  EXPECT_EQ(others_gone.substr(8, 4), behind.substr(8, 4));
  EXPECT_EQ(others_gone.substr(12, 1), "l") << others_gone;  // behind nobody: looked for again...
  EXPECT_EQ(others_gone.substr(13), "ttt") << others_gone;   // ...and found where they show
}

// The shared clip's walk: its root's mean place.
Eigen::Vector3d WalkCentre() {
  const Fixture& f = Shared();
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (const ClipFrame& t : f.truth.frames) centre += t.joints_mm.col(0) / f.truth.frames.size();
  return centre;
}

// One camera `height_mm` up and 9 m back from the walk, looking down on it (as over a plaza).
Camera OverTheWalk(double height_mm) {
  const Eigen::Vector3d centre = WalkCentre();
  return LookAtCamera("cam0", 320, 240, 500, {centre.x(), height_mm, centre.z() - 9000}, {centre.x(), 900, centre.z()});
}

// The test walk's kFrames frames rendered through one camera into `dir`/clip; its truth.
ClipGroundTruth RenderThrough(const Camera& camera, const fs::path& dir) {
  const Walk0701 walk;
  ClipOptions clip;
  clip.max_frames = kFrames;
  clip.contact_sheet = false;
  RenderClip(walk.skeleton, walk.motion, walk.source, {camera}, clip, (dir / "clip").string());
  return ReadGroundTruth(dir / "clip" / "ground_truth.json");
}

// One camera 6 m up, 9 m back, looking down on the walk (as over a plaza); someone tracked
// with the walker stands in front of their legs from the first frame to frame 15 (several
// people at once: the masks lose those pixels and the frames mark them hidden, as
// MultiTracker's births and restarts see them). The start places the walker by the head
// at an adult's height (person_locator.h) and, their height unmeasured, holds their size
// at that guess while the feet stay hidden: tracked within 300 mm of the truth all along
// (measured: up to 250 mm), the size within 3% of the guess. Not told what hides the legs,
// the start reads the thighs' cut as the feet and places the walker 523 mm away, and the
// track stays 450-560 mm off while they are hidden. (From the default ring's cameras, near
// a head's height, an adult's height places nobody well: 3.9 m off; 6.5 m not told.)
TEST(Tracker, AStartWithTheLegsHiddenByOthersIsPlacedByTheHead) {
  const Camera above = OverTheWalk(6000);
  test::TempDir dir;
  const ClipGroundTruth truth = RenderThrough(above, dir.path());
  const auto run = [&](bool told, std::vector<double>* size) {
    const std::unique_ptr<Tracker> held = SharedTracker(100, 3, &truth.cameras);
    Tracker& tracker = *held;
    std::vector<Frame> frames;
    for (int k = 0; k < kFrames; ++k) {
      frames.push_back(ClipFrameAt(truth, dir.path() / "clip", k));
      if (k > 15) continue;
      for (cv::Mat& mask : frames.back().masks) {
        const cv::Rect box = cv::boundingRect(mask);
        const cv::Mat hidden = HideFrom(&mask, box.y + box.height * 3 / 5);  // the thighs and below
        if (told) frames.back().hidden.push_back(hidden);
      }
    }
    EXPECT_TRUE(tracker.StartFromFrames(std::vector<Frame>(frames.begin(), frames.begin() + 5)));
    std::vector<double> error;
    for (const Frame& frame : frames) {
      const TrackedFrame out = tracker.Step(frame);
      const Eigen::Vector3d d = out.state.size() ? Eigen::Vector3d(out.joints_mm.col(0) - truth.frames[out.index].joints_mm.col(0))
                                                 : Eigen::Vector3d::Constant(1e9);
      error.push_back(std::hypot(d.x(), d.z()));
      if (size) size->push_back(out.size);
    }
    return error;
  };
  std::vector<double> size;
  const std::vector<double> told = run(true, &size), untold = run(false, nullptr);
  const double worst = *std::max_element(told.begin(), told.end());
  std::printf("legs hidden by others (frames 0-15): root error at most %.0f mm, size %.3f-%.3f while hidden; not "
              "told: %.0f mm at the first frame\n",
              worst, *std::min_element(size.begin(), size.begin() + 16), *std::max_element(size.begin(), size.begin() + 16),
              untold.front());
  EXPECT_LT(worst, 300);
  for (int k = 0; k <= 15; ++k) EXPECT_NEAR(size[k], 1.0, 0.03) << k;
  EXPECT_GT(untold.front(), 400);
}

// A pillar painted behind the walk (its foot 30 rows above the farthest the walker's feet
// go), which the walker's head and shoulders cover all along: a body in front of a painted
// object is judged on the pixels it covers (occluder_layers.h), so the track is the one
// without the painting, frame for frame. While a painting hid its pixels from every body,
// the walker's head over the pillar was no evidence, and a joint moved by up to 172 mm.
TEST(Tracker, AnObjectPaintedBehindTheWalkChangesNothing) {
  const Camera above = OverTheWalk(6000);
  test::TempDir dir;
  const ClipGroundTruth truth = RenderThrough(above, dir.path());
  // Over the walker's path (they walk straight away from the camera), from the top of the
  // image down to 30 rows above the farthest their feet go.
  cv::Rect walked;
  int farthest_feet = above.height;
  for (int k = 0; k < kFrames; ++k) {
    const cv::Rect blob = cv::boundingRect(ClipFrameAt(truth, dir.path() / "clip", k).masks[0]);
    walked |= blob;
    farthest_feet = std::min(farthest_feet, blob.y + blob.height);
  }
  cv::Mat painting = cv::Mat::zeros(above.height, above.width, CV_8UC1);
  painting(cv::Rect(walked.x + walked.width / 3, 0, walked.width / 3, farthest_feet - 30)).setTo(255);
  ASSERT_GT(cv::countNonZero(painting(walked)), 100);
  const auto run = [&](bool painted) {
    const std::unique_ptr<Tracker> tracker = SharedTracker(100, 3, &truth.cameras);
    std::vector<Frame> frames;
    for (int k = 0; k < kFrames; ++k) {
      frames.push_back(ClipFrameAt(truth, dir.path() / "clip", k));
      if (painted) frames.back().hidden = {painting.clone()};
    }
    EXPECT_TRUE(tracker->StartFromFrames(std::vector<Frame>(frames.begin(), frames.begin() + 5)));
    std::vector<Eigen::Matrix3Xd> joints;
    for (const Frame& frame : frames) joints.push_back(tracker->Step(frame).joints_mm);
    return joints;
  };
  const std::vector<Eigen::Matrix3Xd> plain = run(false), painted = run(true);
  ASSERT_EQ(plain.size(), painted.size());
  double most = 0;
  for (size_t k = 0; k < plain.size(); ++k) {
    ASSERT_EQ(plain[k].cols(), painted[k].cols()) << k;
    if (plain[k].cols() > 0) most = std::max(most, (plain[k] - painted[k]).cwiseAbs().maxCoeff());
  }
  EXPECT_EQ(most, 0.0) << "the painting moved a joint by up to " << most << " mm";
}

// A camera 4 m up over the walk; the track starts on the walker's head but with a body too
// short (size 0.76) placed farther along the head's line of sight (1.08 m), where it
// draws the same head (vtest.avi: a walker beside another drew head to waist, 4.6 m too
// far, for 100 frames, while their build learnt short legs and a coat). The second looks
// (every 5 frames) read the walker's place from their feet and their height from head and
// feet, and move a share of the particles there with that size, although farther than a
// walker goes between looks: the silhouettes take them. Oracle: the root's mean distance
// from the truth over frames 5-14 (after the first look), mean of seeds 1-8: measured 135
// mm (7 seeds 54-172; seed 4 at 421, whose first look the annealing dropped).
// Without (the place moved only within a walk's reach, the size kept) the silhouettes
// alone pull the estimate in at about 60 mm a frame: 467 (376-552). With the merged-blob
// check on pixels alone (TrackerOptions::relocate_merged: the blob against the estimate's
// drawing, not against it for its height), the too-small drawing made the walker's own
// blob look like two people's in seeds 2 and 5 (1.61 times its pixels): 204.
TEST(Tracker, AnEstimateTooShortAndTooFarIsBroughtToTheWalker) {
  const Fixture& f = Shared();
  const Camera above = OverTheWalk(4000);
  test::TempDir dir;
  const ClipGroundTruth truth = RenderThrough(above, dir.path());
  double mean_of_seeds = 0;
  constexpr int kSeeds = 8;
  for (uint64_t seed = 1; seed <= kSeeds; ++seed) {
    const std::unique_ptr<Tracker> held = SharedTracker(100, seed, &truth.cameras);
    Tracker& tracker = *held;
    InitialGuess guess = TruthGuess(truth, *f.loaded, tracker.state_model());
    // Along the line of sight through the head's top: a head at 0.76 / size of its height.
    const double head_mm = truth.frames[0].joints_mm.row(1).maxCoeff();
    const double shrink = 0.76 / guess.size;
    const Eigen::Vector3d eye = above.CentreInWorld();
    const Eigen::Vector2d below_eye(eye.x(), eye.z());
    guess.floor_mm = below_eye + (guess.floor_mm - below_eye) * (eye.y() - shrink * head_mm) / (eye.y() - head_mm);
    guess.size = 0.76, guess.size_std = 0.01, guess.floor_std_mm = 30;
    const double start_off = (guess.floor_mm - truth.frames[0].joints_mm.col(0)({0, 2})).norm();
    EXPECT_GT(start_off, 1000);
    tracker.StartAt(guess);
    double mean_mm = 0, error_at_end = 0;  // over frames 5-14; at the last
    std::string line;
    for (int k = 0; k < kFrames; ++k) {
      const TrackedFrame out = tracker.Step(ClipFrameAt(truth, dir.path() / "clip", k));
      ASSERT_TRUE(out.state.size()) << k;
      const Eigen::Vector3d d = out.joints_mm.col(0) - truth.frames[k].joints_mm.col(0);
      const double error = std::hypot(d.x(), d.z());
      line += " " + std::to_string(static_cast<int>(error));
      error_at_end = error;
      if (k >= 5 && k < 15) mean_mm += error / 10;
    }
    std::printf("seed %d: started %.0f mm off at size 0.76; root off by (mm):%s\n", static_cast<int>(seed), start_off,
                line.c_str());
    EXPECT_LT(error_at_end, 300) << "seed " << seed;
    mean_of_seeds += mean_mm / kSeeds;
  }
  std::printf("root off by %.0f mm over frames 5-14, mean of %d seeds\n", mean_of_seeds, kSeeds);
  EXPECT_LT(mean_of_seeds, 170);
}

// A second walker in view: the walker's own silhouette in camera 0, drawn a third larger
// (nearer the camera, so the strongest evidence) and `offset(k)` px aside at frame k.
// One camera, so the copy is a person standing somewhere else on the floor.
std::vector<Frame> TwoWalkers(const std::function<int(int)>& offset) {
  const Fixture& f = Shared();
  std::vector<Frame> frames;
  for (int k = 0; k < kFrames; ++k) {
    Frame frame = ClipFrameAt(f.truth, f.clip, k);
    frame.masks.resize(1);
    cv::Mat& mask = frame.masks[0];
    const cv::Rect box = cv::boundingRect(mask);
    cv::Mat big;
    cv::resize(mask(box), big, cv::Size(), 1.3, 1.3, cv::INTER_NEAREST);
    const cv::Rect to = cv::Rect(box.x + offset(k), box.y + box.height - big.rows + 4, big.cols, big.rows) &
                        cv::Rect(0, 0, mask.cols, mask.rows);
    if (!to.empty()) {
      cv::Mat target = mask(to);
      cv::bitwise_or(target, big(cv::Rect(to.x - (box.x + offset(k)), to.y - (box.y + box.height - big.rows + 4),
                                          to.width, to.height)),
                     target);
    }
    frames.push_back(frame);
  }
  return frames;
}

// Each frame's horizontal root error (mm) of a one-camera tracker choosing `person`.
std::vector<double> TrackOneOfTwo(const std::vector<Frame>& frames, const PersonPreference& person) {
  const Fixture& f = Shared();
  TrackerOptions options;
  options.annealing.particles = 100;
  options.annealing.seed = 3;
  options.person = person;
  Tracker tracker(*f.loaded, {f.truth.cameras[0]}, options);
  std::vector<double> error;
  tracker.StartFromFrames(std::vector<Frame>(frames.begin(), frames.begin() + 15));
  for (const Frame& frame : frames) {
    const TrackedFrame out = tracker.Step(frame);
    const Eigen::Vector3d d = out.state.size() ? Eigen::Vector3d(out.joints_mm.col(0) - f.truth.frames[out.index].joints_mm.col(0))
                                               : Eigen::Vector3d::Constant(1e9);
    error.push_back(std::hypot(d.x(), d.z()));
  }
  return error;
}

// `--person X,Y` chooses the walker at that pixel over a larger one beside them, and the
// choice is kept while the other walker passes in front (their blobs merge for a few
// frames). Without a choice the larger one is taken (so the test can fail).
TEST(Tracker, KeepsThePersonChosenWhenAnotherWalksBy) {
  const Fixture& f = Shared();
  const cv::Rect first = cv::boundingRect(ClipFrameAt(f.truth, f.clip, 0).masks[0]);
  const int side = first.x + first.width / 2 < f.truth.cameras[0].width / 2 ? 1 : -1;  // where there is room
  PersonPreference chosen;
  chosen.kind = PersonPreference::Kind::kNearPixel;
  chosen.pixel = Eigen::Vector2d(first.x + first.width / 2, first.y + first.height / 2);
  for (const bool crossing : {false, true}) {
    // Apart: 2 box widths aside throughout. Crossing: from there to as far the other side.
    const auto offset = [&](int k) {
      const double apart = 2.0 * side * first.width;
      return static_cast<int>(crossing ? apart * (1 - 2.0 * k / (kFrames - 1)) : apart);
    };
    const std::vector<Frame> frames = TwoWalkers(offset);
    const std::vector<double> strongest = TrackOneOfTwo(frames, PersonPreference());
    const std::vector<double> kept = TrackOneOfTwo(frames, chosen);
    std::printf("%s: root error with the choice: max %.0f mm, last %.0f mm; without it: first %.0f mm\n",
                crossing ? "crossing" : "apart", *std::max_element(kept.begin(), kept.end()), kept.back(),
                strongest.front());
    if (!crossing) {
      EXPECT_GT(strongest.front(), 500);  // the other walker is the strongest
    }
    for (int k = 0; k < kFrames; ++k) EXPECT_LT(kept[k], 400) << (crossing ? "crossing, frame " : "apart, frame ") << k;
  }
}

// The person leaves the view (after frame 9 the video skips 3 s, so the prediction is
// metres on, out of the image) while someone else walks in it:
// once the estimate has been drawn in no camera for lost_frames frames, the track ends and
// the one in view is tracked. (A prediction walking on out of view used to be reported,
// "predicted", for the rest of the video while others walked by.)
TEST(Tracker, APersonWhoLeftTheViewGivesWayToSomeoneInIt) {
  const Fixture& f = Shared();
  TrackerOptions options;
  options.annealing.particles = 100;
  options.annealing.seed = 3;
  Tracker tracker(*f.loaded, {f.truth.cameras[0]}, options);
  std::vector<Frame> frames;
  for (int k = 0; k < kFrames; ++k) {
    Frame frame = ClipFrameAt(f.truth, f.clip, k);
    frame.masks.resize(1);
    if (k >= 10) {
      frame.time_s += 3;
      cv::Mat& mask = frame.masks[0];  // someone else: the walker's silhouette 55 px aside
      mask = ShiftedRight(mask, 55);
    }
    frames.push_back(frame);
  }
  ASSERT_TRUE(tracker.StartFromFrames(std::vector<Frame>(frames.begin(), frames.begin() + 5)));
  std::string line;
  TrackedFrame out;
  for (const Frame& frame : frames) {
    out = tracker.Step(frame);
    line += TrackStatusName(out.status)[0];
  }
  std::printf("statuses %s, last IoU %.2f\n", line.c_str(), out.MeanIou());
  EXPECT_NE(line.find('l', 10), std::string::npos);  // the track ended...
  EXPECT_EQ(out.status, TrackStatus::kTracked);      // ...and the one in view is tracked
  EXPECT_GT(out.MeanIou(), 0.3);
}

// A restart looks for the person within a brisk walk (1 m and 2 m/s) of where they were
// last explained well. The walker (one camera) vanishes at frame 8 (the masks empty:
// lost), and from frame 10 their silhouette shows 65 px aside, about 1.3 m from the last
// good place, the frames 1/120 s apart: no restart on it while a brisk walk could not have
// got there; from frame 18, half a second later, a restart on it. (Restarted at once, a
// tuning clip's walker lost behind a pillar was put on a ball passing 4.2 m away.)
TEST(Tracker, ARestartLooksWithinABriskWalkOfTheLastGoodPlace) {
  const Fixture& f = Shared();
  TrackerOptions options;
  options.annealing.particles = 100;
  options.annealing.seed = 3;
  const Camera& camera = f.truth.cameras[0];
  Tracker tracker(*f.loaded, {camera}, options);
  const int aside = 65;  // behind the walker, who walks to the left
  std::vector<Frame> frames;
  for (int k = 0; k < kFrames; ++k) {
    Frame frame = ClipFrameAt(f.truth, f.clip, k);
    frame.masks.resize(1);
    if (k >= 8) {
      frame.time_s = f.truth.frames[7].time_s + (k - 7) / 120.0 + (k >= 18 ? 0.5 : 0);
      cv::Mat& mask = frame.masks[0];
      cv::Mat moved;
      cv::warpAffine(mask, moved, cv::Matx23d(1, 0, aside, 0, 1, 0), mask.size(), cv::INTER_NEAREST);
      mask = k < 10 ? cv::Mat::zeros(mask.size(), CV_8UC1) : moved;
    }
    frames.push_back(frame);
  }
  ASSERT_TRUE(tracker.StartFromFrames(std::vector<Frame>(frames.begin(), frames.begin() + 5)));
  std::string line;
  Eigen::Vector2d last_good = Eigen::Vector2d::Zero();
  double last_good_s = 0;
  std::vector<double> gap;  // per frame: the whole sighting's distance beyond a brisk walk, mm
  for (const Frame& frame : frames) {
    const TrackedFrame out = tracker.Step(frame);
    line += TrackStatusName(out.status)[0];
    if (frame.index < 8) {
      last_good = Eigen::Vector2d(out.joints_mm(0, 0), out.joints_mm(2, 0));
      last_good_s = frame.time_s;
    }
    const PersonSighting seen = LocatePerson({camera}, frame.masks);
    gap.push_back(seen.found && seen.whole
                      ? (seen.floor_mm - last_good).norm() - (1000 + 2000 * (frame.time_s - last_good_s))
                      : 0);
  }
  std::printf("statuses %s; the sighting beyond a brisk walk by %.0f mm at frame 10, %.0f mm at the last\n",
              line.c_str(), gap[10], gap.back());
  ASSERT_EQ(line.substr(0, 8), std::string(8, 't'));
  for (int k = 10; k < kFrames; ++k) {
    if (gap[k] > 100) {
      EXPECT_EQ(line[k], 'l') << k;  // out of reach: not them
    } else if (gap[k] < -100) {
      EXPECT_NE(line[k], 'l') << k;  // within it: restarted on
    }
  }
  EXPECT_GT(gap[10], 100);
  EXPECT_LT(gap.back(), -100);
}

// A walker who has left the view but for a quarter of their body is lost, not tracked on
// that quarter. The side camera's image is cut 3/4 of the way across the walker's box at
// the first frame (the camera's principal point moved with the masks, so the geometry is
// the clip's): what shows is a strip of them the whole clip long, which the estimate,
// started on the truth, explains well. Less than half of the estimate in view for
// lost_frames frames, the track ends. (It went on "tracked": on a webcam clip a body
// almost wholly below the image fitted the walker's shadow with a foot, 20 frames.)
TEST(Tracker, AWalkerAlmostWhollyOutOfViewIsLostNotTrackedOnWhatShows) {
  const Fixture& f = Shared();
  TrackerOptions options;
  options.annealing.particles = 100;
  options.annealing.seed = 2;
  const cv::Rect box = cv::boundingRect(ClipFrameAt(f.truth, f.clip, 0).masks[0]);
  const int cut = box.x + box.width * 3 / 4;
  Camera camera = f.truth.cameras[0];
  camera.cx -= cut;
  camera.width -= cut;
  Tracker tracker(*f.loaded, {camera}, options);
  tracker.StartAt(TruthGuess(f.truth, *f.loaded, tracker.state_model()));
  std::string line;
  double best_iou = 0;
  for (int k = 0; k < kFrames; ++k) {
    Frame frame = ClipFrameAt(f.truth, f.clip, k);
    frame.masks = {frame.masks[0](cv::Rect(cut, 0, camera.width, camera.height)).clone()};
    const TrackedFrame out = tracker.Step(frame);
    line += TrackStatusName(out.status)[0];
    if (k < 5) best_iou = std::max(best_iou, out.MeanIou());
  }
  std::printf("statuses %s (best IoU at the start %.2f)\n", line.c_str(), best_iou);
  EXPECT_GT(best_iou, 0.3);  // what shows is explained: the old rule kept it "tracked"
  EXPECT_EQ(line.substr(line.size() - 10), std::string(10, 'l'));
}

// The start's guess from the first 15 frames' masks against the clip's truth: the place
// at the first frame (the fitted walk through the places found), the heading and speed
// of travel.
TEST(Tracker, GuessReadsThePlaceHeadingAndSpeedOfTheWalk) {
  const Fixture& f = Shared();
  const ClipGroundTruth& truth = f.truth;
  const Tracker tracker(*f.loaded, truth.cameras, TrackerOptions{});
  std::vector<Frame> frames;
  for (int k = 0; k < 15; ++k) frames.push_back(ClipFrameAt(truth, f.clip, k));
  InitialGuess guess;
  ASSERT_TRUE(tracker.Guess(frames, &guess));
  const Eigen::Vector3d a = truth.frames[0].joints_mm.col(0), b = truth.frames[14].joints_mm.col(0);
  const Eigen::Vector2d travel(b.x() - a.x(), b.z() - a.z());
  const double seconds = truth.frames[14].time_s - truth.frames[0].time_s;
  const double heading = std::atan2(travel.x(), travel.y());
  std::printf("guess: floor %.0f mm off, heading %.1f deg off, speed %.0f (truth %.0f) mm/s, size %.2f\n",
              (guess.floor_mm - Eigen::Vector2d(a.x(), a.z())).norm(),
              std::remainder(guess.heading_rad - heading, 2 * std::numbers::pi) * 180 / std::numbers::pi,
              guess.speed_mm_s, travel.norm() / seconds, guess.size);
  EXPECT_LT((guess.floor_mm - Eigen::Vector2d(a.x(), a.z())).norm(), 300);  // the locator's error
  EXPECT_LT(std::abs(std::remainder(guess.heading_rad - heading, 2 * std::numbers::pi)), 20 * std::numbers::pi / 180);
  EXPECT_NEAR(guess.speed_mm_s, travel.norm() / seconds, 0.25 * travel.norm() / seconds);
  EXPECT_LT(guess.heading_std_rad, std::numbers::pi);  // a heading was read, not "any"
}

// Nobody is started on a flicker: a walker's blob seen in one frame of three, by turns at
// the left and the right of one camera's view (leaves in a tree, a segmentation's
// noise), is followed in at most 3 of any 15 frames, fewer than
// TrackerOptions::start_seen_frames. The walker then in view every frame is started once
// seen in that many. Before the rule the first flicker was started on at once and
// "tracked".
TEST(Tracker, NobodyIsStartedOnAPersonShapedFlicker) {
  const Fixture& f = Shared();
  const Camera& camera = f.truth.cameras[0];
  TrackerOptions options;
  options.annealing.particles = 100;
  Tracker tracker(*f.loaded, {camera}, options);
  constexpr int kFlicker = 15;
  std::string line;
  for (int k = 0; k < kFrames; ++k) {
    Frame frame = ClipFrameAt(f.truth, f.clip, k);
    frame.masks.resize(1);
    cv::Mat& mask = frame.masks[0];
    if (k < kFlicker) {
      // The walker's blob moved to a quarter of the width from the left or the right edge.
      const cv::Rect box = cv::boundingRect(mask);
      const int centre = (k / 3) % 2 == 0 ? camera.width / 4 : 3 * camera.width / 4;
      const cv::Mat shift = (cv::Mat_<double>(2, 3) << 1, 0, centre - (box.x + box.width / 2), 0, 1, 0);
      cv::Mat moved;
      cv::warpAffine(mask, moved, shift, mask.size(), cv::INTER_NEAREST);
      mask = k % 3 == 0 ? moved : cv::Mat::zeros(mask.size(), mask.type());
    }
    line += TrackStatusName(tracker.Step(frame).status)[0];
  }
  std::printf("statuses %s (the walker from frame %d)\n", line.c_str(), kFlicker);
  EXPECT_EQ(line.substr(0, kFlicker), std::string(kFlicker, 'l'));
  // Started once followed in start_seen_frames frames, and explained from then on.
  const size_t first = line.find('t', kFlicker);
  ASSERT_NE(first, std::string::npos);
  EXPECT_LE(first, static_cast<size_t>(kFlicker + options.start_seen_frames + 1));
  EXPECT_EQ(line.substr(line.size() - 3), "ttt");
}

// A start from nobody whose estimates never explain the masks to lost_iou is never
// reported tracked: its frames are predicted until one does. Here lost_iou is set above
// any IoU the walker's estimates reach, so none does; they were "tracked" until the loss
// rule ran out (lost_frames), and again after each restart.
TEST(Tracker, AStartNeverExplainedWellIsNotReportedTracked) {
  const Fixture& f = Shared();
  TrackerOptions options;
  options.annealing.particles = 100;
  options.lost_iou = 0.97;
  Tracker tracker(*f.loaded, f.truth.cameras, options);
  std::string line;
  double best_iou = 0;
  for (int k = 0; k < kFrames; ++k) {
    const TrackedFrame out = tracker.Step(ClipFrameAt(f.truth, f.clip, k));
    line += TrackStatusName(out.status)[0];
    if (out.state.size()) best_iou = std::max(best_iou, out.MeanIou());
  }
  std::printf("statuses %s (the best IoU %.2f)\n", line.c_str(), best_iou);
  ASSERT_LT(best_iou, options.lost_iou);
  ASSERT_NE(line.find('p'), std::string::npos) << "a start must be made";
  EXPECT_EQ(line.find('t'), std::string::npos);
}

// A start from frames already past (a person born while others are tracked) is where the
// walker is at the last of them, not where they were at the first: half a second on, the
// walker of the clip has gone over half a metre.
TEST(Tracker, AStartFromPastFramesIsWhereTheWalkerIsAtTheLast) {
  const Fixture& f = Shared();
  const ClipGroundTruth& truth = f.truth;
  const Tracker tracker(*f.loaded, truth.cameras, TrackerOptions{});
  std::vector<Frame> frames;
  for (int k = 0; k < 15; ++k) frames.push_back(ClipFrameAt(truth, f.clip, k));
  InitialGuess first, last;
  std::vector<cv::Rect> first_boxes, last_boxes;
  ASSERT_TRUE(tracker.Guess(frames, &first, {}, &first_boxes));
  ASSERT_TRUE(tracker.Guess(frames, &last, {}, &last_boxes, true));
  const Eigen::Vector3d a = truth.frames[0].joints_mm.col(0), b = truth.frames[14].joints_mm.col(0);
  const Eigen::Vector2d at_first(a.x(), a.z()), at_last(b.x(), b.z());
  std::printf("the walk: %.0f mm; the start at the last frame %.0f mm from the walker there (at the first: %.0f)\n",
              (at_last - at_first).norm(), (last.floor_mm - at_last).norm(), (first.floor_mm - at_last).norm());
  ASSERT_GT((at_last - at_first).norm(), 500);
  EXPECT_LT((last.floor_mm - at_last).norm(), 300);  // the locator's error
  EXPECT_LT((first.floor_mm - at_first).norm(), 300);
  // The boxes to look in at the start are the last frame's: each camera's holds the
  // walker's root as drawn there.
  ASSERT_EQ(last_boxes.size(), truth.cameras.size());
  for (size_t c = 0; c < truth.cameras.size(); ++c) {
    Eigen::Vector2d root;
    ASSERT_TRUE(truth.cameras[c].Project(b, &root));
    EXPECT_TRUE(last_boxes[c].contains(cv::Point(static_cast<int>(root.x()), static_cast<int>(root.y())))) << c;
  }
}

// A walker coming into a camera's view from its side: one camera of the clip, its image
// cut at the middle of the walker's box at the first frame on the side they come from (the
// principal point moved with the masks, so the geometry is the clip's). Every frame of the
// clip so cut; `whole` the first where the walker is clear of the cut edge.
struct SideEntry {
  Camera camera;
  std::vector<Frame> frames;
  int whole = -1;
};
SideEntry ComingInFromTheSide() {
  const Fixture& f = Shared();
  const ClipGroundTruth& truth = f.truth;
  // The camera the walker crosses fastest.
  int cam = 0;
  double fastest = 0;
  for (size_t c = 0; c < truth.cameras.size(); ++c) {
    const cv::Rect a = cv::boundingRect(ClipFrameAt(truth, f.clip, 0).masks[c]);
    const cv::Rect b = cv::boundingRect(ClipFrameAt(truth, f.clip, kFrames - 1).masks[c]);
    const double moved = std::abs((b.x + 0.5 * b.width) - (a.x + 0.5 * a.width));
    if (moved > fastest) fastest = moved, cam = static_cast<int>(c);
  }
  const cv::Rect a = cv::boundingRect(ClipFrameAt(truth, f.clip, 0).masks[cam]);
  const cv::Rect b = cv::boundingRect(ClipFrameAt(truth, f.clip, kFrames - 1).masks[cam]);
  const bool rightwards = b.x > a.x;  // coming in from the left edge
  SideEntry entry;
  entry.camera = truth.cameras[cam];
  const int middle = a.x + a.width / 2;
  const cv::Rect kept = rightwards ? cv::Rect(middle, 0, entry.camera.width - middle, entry.camera.height)
                                   : cv::Rect(0, 0, middle + 1, entry.camera.height);
  entry.camera.cx -= kept.x;
  entry.camera.width = kept.width;
  for (int k = 0; k < kFrames; ++k) {
    Frame frame = ClipFrameAt(truth, f.clip, k);
    frame.masks = {frame.masks[cam](kept).clone()};
    const cv::Rect box = cv::boundingRect(frame.masks[0]);
    if (entry.whole < 0 && box.x > 0 && box.x + box.width < kept.width) entry.whole = k;
    entry.frames.push_back(std::move(frame));
  }
  return entry;
}

// Until the walker coming in is wholly in view the blobs are slices (no start is made on
// them); the start at the first frame where they are whole reads their travel from the
// slices before it. It read one frame: any heading, and on the webcam clip 39_10 a start
// 44 degrees off.
TEST(Tracker, AWalkerComingInFromTheSideStartsWithTheirTravel) {
  const Fixture& f = Shared();
  const ClipGroundTruth& truth = f.truth;
  const SideEntry entry = ComingInFromTheSide();
  const int whole = entry.whole;
  ASSERT_GE(whole, 4) << "the walker must come in over some frames";
  ASSERT_LT(whole, kFrames - 1);
  // Up to the first frame where the walker is clear of the cut edge.
  const std::vector<Frame> frames(entry.frames.begin(), entry.frames.begin() + whole + 1);
  const Eigen::Vector3d p = truth.frames[0].joints_mm.col(0), q = truth.frames[whole].joints_mm.col(0);
  const double heading = std::atan2(q.x() - p.x(), q.z() - p.z());
  const auto off_deg = [&](double h) {
    return std::abs(std::remainder(h - heading, 2 * std::numbers::pi)) * 180 / std::numbers::pi;
  };
  TrackerOptions options;
  options.annealing.particles = 100;
  Tracker tracker(*f.loaded, {entry.camera}, options);
  InitialGuess guess;
  ASSERT_TRUE(tracker.Guess(frames, &guess, {}, nullptr, /*at_last=*/true));
  std::printf("whole in view at frame %d: heading %.1f deg off (std %.0f deg), the place %.0f mm off\n", whole,
              off_deg(guess.heading_rad), guess.heading_std_rad * 180 / std::numbers::pi,
              std::hypot(guess.floor_mm.x() - q.x(), guess.floor_mm.y() - q.z()));
  EXPECT_LT(guess.heading_std_rad, std::numbers::pi);  // a heading was read, not "any"
  EXPECT_LT(off_deg(guess.heading_rad), 30);
  EXPECT_LT(std::hypot(guess.floor_mm.x() - q.x(), guess.floor_mm.y() - q.z()), 300);  // the locator's error
  // Stepped frame by frame (nothing started beforehand), the tracker starts there with it.
  for (int k = 0; k <= whole; ++k) {
    const TrackedFrame out = tracker.Step(frames[k]);
    if (k < whole) {
      EXPECT_EQ(out.status, TrackStatus::kLost) << k;
    } else {
      ASSERT_EQ(out.status, TrackStatus::kTracked);
      std::printf("the first frame tracked: heading %.1f deg off\n", off_deg(out.heading_rad));
      EXPECT_LT(off_deg(out.heading_rad), 30);
    }
  }
}

// ...and is tracked in the frames before that start too, while it comes in: the start's
// second pass goes on back into the frames lost before it (StartBackOver's lead-in) while
// it explains them well. Without the lead-in every frame before the start was lost (a
// webcam's walker, head and feet in view, for 13 frames).
TEST(StartBackOver, GoesOnBackIntoTheFramesLostBeforeAStart) {
  const Fixture& f = Shared();
  const SideEntry entry = ComingInFromTheSide();
  ASSERT_GE(entry.whole, 4);
  TrackerOptions options;
  options.annealing.particles = 100;
  options.start_backwards_s = 0.3;  // gone back over within the clip's 25 frames
  Tracker tracker(*f.loaded, {entry.camera}, options);
  StartBackOver hold(&tracker);
  std::vector<StartBackOver::Estimate> given;
  for (const Frame& frame : entry.frames) hold.Add(frame, tracker.Step(frame), &given);
  hold.Flush(&given);
  ASSERT_EQ(given.size(), static_cast<size_t>(kFrames));
  int before = 0;  // frames before the start now tracked
  for (int k = 0; k < kFrames; ++k) {
    const TrackedFrame& e = given[k].estimate;
    ASSERT_EQ(e.index, k);
    if (k >= entry.whole || e.status == TrackStatus::kLost) continue;
    EXPECT_EQ(e.status, TrackStatus::kTracked) << k;
    EXPECT_GE(e.MeanIou(), options.lost_iou) << k;
    const double off = (e.joints_mm.col(0) - f.truth.frames[k].joints_mm.col(0)).norm();
    std::printf("frame %d, before the start at %d: root %.0f mm off, IoU %.2f\n", k, entry.whole, off, e.MeanIou());
    EXPECT_LT(off, 250) << k;
    ++before;
  }
  // The frames just before the start, the walker all but whole in view, at least.
  EXPECT_GE(before, 2);
  for (int k = entry.whole - 2; k < entry.whole; ++k) EXPECT_NE(given[k].estimate.status, TrackStatus::kLost) << k;
}

// The joint-angle refinement's random numbers follow the tracker's seed (they ignored it).
TEST(Tracker, TheSeedReachesTheRefinement) {
  const Fixture& f = Shared();
  const GaitModel* model = f.loaded.get();
  const ClipGroundTruth& truth = f.truth;
  const Frame frame = ClipFrameAt(truth, f.clip, 5);
  const SilhouetteLikelihood likelihood(truth.cameras);
  const BodyModel body(model->skeleton(), {}, "model");
  ThreadPool pool(1);
  std::vector<CameraObservation> observed;
  for (const cv::Mat& mask : frame.masks) observed.push_back(likelihood.Observe(mask, {0, 0, mask.cols, mask.rows}));
  const Eigen::Vector3d latent = model->latent().row(7).transpose();
  const Eigen::VectorXd pose = model->MeanPoses(latent.transpose()).row(0).transpose();
  const Eigen::Vector3d root = truth.frames[5].joints_mm.col(0);
  auto refine = [&](uint64_t seed) {
    RefinementOptions options;
    options.seed = seed;
    PoseRefiner refiner(*model, likelihood, body, options, &pool);
    return refiner.Refine(pose, latent, root.x(), root.z(), 0, 1, 1, observed, 5).pose_deg;
  };
  EXPECT_EQ(refine(1), refine(1));
  EXPECT_NE(refine(1), refine(2));
}

// A walker who turned round where the particles did not (a turn on the spot, a start that
// read the heading backwards): started at the truth's place and size but facing away from
// where the walker faces, and so walking away from where they go, the particles must come
// round within the clip, walking forwards. Two cameras see the body's front from its back;
// the heading's own noise (1 degree a frame, 6 for a tenth) reaches 180 degrees in no clip,
// so only the turns to any heading (TrackerOptions::turn_every) can. Before them the
// heading stayed 164-177 degrees off. When they win is chance (the frames to come round,
// seeds 1-8: 1 to 22), so four seeds are run: each must come round and stay (within 30
// degrees to the end) before the last frames, on average within half the clip, and end
// with a positive cadence (not turned round to face the walker but walking backwards).
TEST(Tracker, AWalkerFacingAwayFromTheParticlesIsComeRoundTo) {
  const Fixture& f = Shared();
  double mean_frames = 0;
  constexpr int kSeeds = 4;
  for (uint64_t seed = 1; seed <= kSeeds; ++seed) {
    Tracker tracker(*f.loaded, f.truth.cameras, [&] {
      TrackerOptions options;
      options.annealing.particles = 150;
      options.annealing.seed = seed;
      return options;
    }());
    InitialGuess guess = TruthGuess(f.truth, *f.loaded, tracker.state_model());
    const double truth_heading = guess.heading_rad;
    guess.heading_rad += std::numbers::pi;
    guess.coordinates.resize(0);  // the pose from the masks
    tracker.StartAt(guess);
    const auto off_deg = [&](double heading) {
      return std::abs(std::remainder(heading - truth_heading, 2 * std::numbers::pi)) * 180 / std::numbers::pi;
    };
    std::string line;
    int round = 0;  // the first frame from which the heading stays within 30 degrees
    double cadence = 0;
    for (int k = 0; k < kFrames; ++k) {
      const TrackedFrame out = tracker.Step(ClipFrameAt(f.truth, f.clip, k));
      cadence = out.state[tracker.state_model().placement().rate];
      line += " " + std::to_string(static_cast<int>(off_deg(out.heading_rad)));
      if (off_deg(out.heading_rad) >= 30) round = k + 1;
    }
    std::printf("seed %d: heading off by (deg):%s; cadence at the end %.2f\n", static_cast<int>(seed), line.c_str(),
                cadence);
    EXPECT_LT(round, kFrames - 2) << "seed " << seed;
    EXPECT_GT(cadence, 0) << "seed " << seed;
    mean_frames += round / static_cast<double>(kSeeds);
  }
  EXPECT_LT(mean_frames, kFrames / 2.0);
}

// A walker going backwards: the test subject's walk played in reverse (walking backwards
// is close to that; subject 131's moonwalks are it), 40 frames from the clip's two cameras.
// Tracked from the masks, the estimate must face where the walker faces, not where they
// go. The start reads the heading from the travel (people walk forwards), so the particles
// begin facing away and walking forwards, which moves them as the walker moves. Particles
// turned to any heading (TrackerOptions::turn_every, on by default) that face the walker
// walk the wrong way until the travel check turns their cadence (TrackerOptions::travel):
// faced in 14 frames. Particles turned round walking backwards (reverse_every, off by
// default) face them in one. Without either the hips stay turned round to the end
// (checked here too, so that the walk tested is one that needs them). Oracle: the line
// through the hips, estimate against truth, on average over the last 10 frames.
TEST(Tracker, AWalkerGoingBackwardsIsTrackedFacingTheirWay) {
  const Fixture& f = Shared();
  constexpr int kBackFrames = 40;
  Walk0701 walk;
  const int mocap_frames = kBackFrames * 4;  // 120 fps to the clip's 30
  ASSERT_GE(walk.motion.values.rows(), mocap_frames);
  walk.motion.values = RowMatrixXd(walk.motion.values.topRows(mocap_frames).colwise().reverse());
  test::TempDir dir;
  RenderClip(walk.skeleton, walk.motion, walk.source, {}, SmallClip(kBackFrames), (dir.path() / "clip").string());
  const ClipGroundTruth truth = ReadGroundTruth(dir.path() / "clip" / "ground_truth.json");
  const auto hips_deg = [](const Skeleton& bones, const Eigen::Matrix3Xd& joints) {
    const Eigen::Vector3d across = joints.col(bones.FindBone("lhipjoint")) - joints.col(bones.FindBone("rhipjoint"));
    return std::atan2(across.x(), across.z()) * 180 / std::numbers::pi;
  };
  const auto hips_off_deg = [&](int turn_every, int reverse_every) {
    TrackerOptions options;
    options.annealing.particles = 150;
    options.turn_every = turn_every;
    options.reverse_every = reverse_every;
    Tracker tracker(*f.loaded, truth.cameras, options);
    std::vector<Frame> frames;
    for (int k = 0; k < kBackFrames; ++k) frames.push_back(ClipFrameAt(truth, dir.path() / "clip", k));
    EXPECT_TRUE(tracker.StartFromFrames({frames.begin(), frames.begin() + 15}));
    double off = 0;
    std::string line;
    for (int k = 0; k < kBackFrames; ++k) {
      const TrackedFrame out = tracker.Step(frames[k]);
      const double d = std::abs(std::remainder(
          hips_deg(f.loaded->skeleton(), out.joints_mm) - hips_deg(walk.skeleton, truth.frames[k].joints_mm), 360.0));
      line += " " + std::to_string(static_cast<int>(d));
      if (k >= kBackFrames - 10) off += d / 10;
    }
    std::printf("turn_every %d, reverse_every %d: hips off by (deg):%s\n", turn_every, reverse_every, line.c_str());
    return off;
  };
  EXPECT_GT(hips_off_deg(0, 0), 90);
  EXPECT_LT(hips_off_deg(TrackerOptions{}.turn_every, TrackerOptions{}.reverse_every), 30);
  EXPECT_LT(hips_off_deg(0, 50), 30);
}

// A walker who stops for a second (07_01 held half a second in, jgpm render --pause) is
// tracked standing: with the pace (TrackerOptions::pace) the cadence falls towards a stand
// within the stop, where without it the dynamics kept stepping at 0.6 cycles a second and
// the annealing pulled the walker back every frame; either way the root stays on the
// standing walker, and the walk goes on afterwards. Expected with the pace: the speed seen
// over the 0.5 s window falls under stop_speed_mm_s (300) about 0.4 s into the stop (the
// walker went 1.3 m/s), then the cadence moves a 15th of the way to 0.05 a frame for the
// remaining 0.6 s, from 0.9: 0.05 + 0.85 (14/15)^18 = 0.30 at the stop's end.
TEST(Tracker, AWalkerWhoStopsIsTrackedStandingStill) {
  const Fixture& f = Shared();
  constexpr int kStopFrame = 15, kStopFrames = 30, kClipFrames = 55;
  const Walk0701 walk;
  ClipOptions clip = SmallClip(kClipFrames);
  clip.pauses = {{kStopFrame / 30.0, kStopFrames / 30.0}};
  test::TempDir dir;
  RenderClip(walk.skeleton, walk.motion, walk.source, {}, clip, (dir.path() / "clip").string());
  const ClipGroundTruth truth = ReadGroundTruth(dir.path() / "clip" / "ground_truth.json");
  struct Run {
    double rate_at_end_of_stop = 0, worst_root_in_stop_mm = 0, root_at_end_mm = 0;
  };
  const auto run = [&](bool pace) {
    TrackerOptions options;
    options.annealing.particles = 150;
    options.pace = pace;
    Tracker tracker(*f.loaded, truth.cameras, options);
    std::vector<Frame> frames;
    for (int k = 0; k < kClipFrames; ++k) frames.push_back(ClipFrameAt(truth, dir.path() / "clip", k));
    EXPECT_TRUE(tracker.StartFromFrames({frames.begin(), frames.begin() + kStopFrame}));
    const int rate = tracker.state_model().placement().rate;
    Run r;
    std::string line;
    for (int k = 0; k < kClipFrames; ++k) {
      const TrackedFrame out = tracker.Step(frames[k]);
      EXPECT_EQ(out.status, TrackStatus::kTracked) << k;
      const double root = (out.joints_mm.col(0) - truth.frames[k].joints_mm.col(0)).norm();
      if (k >= kStopFrame && k < kStopFrame + kStopFrames) r.worst_root_in_stop_mm = std::max(r.worst_root_in_stop_mm, root);
      if (k == kStopFrame + kStopFrames - 1) r.rate_at_end_of_stop = out.state[rate];
      if (k == kClipFrames - 1) r.root_at_end_mm = root;
      if (k % 5 == 4) line += " " + std::to_string(out.state[rate]).substr(0, 5);
    }
    std::printf("pace %d: cadence every 5th frame%s; root off by %.0f mm at worst while standing, %.0f at the end\n",
                pace, line.c_str(), r.worst_root_in_stop_mm, r.root_at_end_mm);
    return r;
  };
  const Run paced = run(true), unpaced = run(false);
  EXPECT_LT(std::abs(paced.rate_at_end_of_stop), 0.35);
  EXPECT_GT(std::abs(unpaced.rate_at_end_of_stop), 0.4);
  for (const Run& r : {paced, unpaced}) {
    EXPECT_LT(r.worst_root_in_stop_mm, 150);
    EXPECT_LT(r.root_at_end_mm, 150);
  }
}

// A clip of the test subject's walk rendered with --shadow (seed 3), its truth and the
// light it was rendered with (ClipScene's).
struct ShadowClip {
  test::TempDir dir;
  ClipGroundTruth truth;
  Eigen::Vector3d light;
  explicit ShadowClip(ClipOptions options) {
    const Walk0701 walk;
    options.scene.shadow = true;
    options.seed = 3;
    RenderClip(walk.skeleton, walk.motion, walk.source, {}, options, clip().string());
    truth = ReadGroundTruth(clip() / "ground_truth.json");
    light = ClipScene(options.scene, truth.cameras, {truth.frames[0].joints_mm}, options.seed).light();
  }
  fs::path clip() const { return dir.path() / "clip"; }
};

// Masks that keep the walker's shadow (the clip's observed masks with --shadow): the
// tracker finds the light that cast it (the clip's own, ClipScene's) and draws each body's
// shadow from then on, which explains the masks better than the same run without.
TEST(Tracker, AShadowInTheMasksIsFoundAndDrawnWithEveryBody) {
  const Fixture& f = Shared();
  constexpr int kClipFrames = 60;
  const ShadowClip shadowed(SmallClip(kClipFrames));
  const ClipGroundTruth& truth = shadowed.truth;
  const Eigen::Vector3d& light = shadowed.light;
  const auto run = [&](bool shadow, std::optional<Eigen::Vector3d>* found, int* found_at, TrackRun* written) {
    TrackerOptions options;
    options.annealing.particles = 150;
    options.shadow.enabled = shadow;
    options.shadow.every = 2;
    Tracker tracker(*f.loaded, truth.cameras, options);
    double cost = 0;  // over the last 15 frames
    for (int k = 0; k < kClipFrames; ++k) {
      written->frames.push_back(tracker.Step(ClipFrameAt(truth, shadowed.clip(), k)));
      if (k >= kClipFrames - 15)
        for (const CameraScore& c : written->frames.back().cameras) cost += c.cost / 15;
    }
    *found = tracker.shadow_light().light();
    *found_at = tracker.shadow_light_frame();
    return cost;
  };
  std::optional<Eigen::Vector3d> found, none;
  int found_at = -1, never = -1;
  TrackRun with_run, without_run;
  with_run.cameras = without_run.cameras = truth.cameras;
  const double with = run(true, &found, &found_at, &with_run), without = run(false, &none, &never, &without_run);
  ASSERT_TRUE(found.has_value());
  const double off_deg = std::acos(std::clamp(found->dot(light), -1.0, 1.0)) * 180 / std::numbers::pi;
  std::printf("the light found at frame %d, %.1f degrees off; the last 15 frames cost %.3f a frame with the shadow "
              "drawn, %.3f without\n", found_at, off_deg, with, without);
  EXPECT_LT(off_deg, 6);
  EXPECT_FALSE(none.has_value());
  EXPECT_LT(with, 0.8 * without);
  // poses.json says which light, and when it was found.
  const nlohmann::json written = PosesJson(with_run, f.loaded->skeleton(), std::nullopt)["summary"]["shadow_light"];
  ASSERT_TRUE(written.is_object()) << written;
  EXPECT_EQ(written["found_at_frame"].get<int>(), found_at);
  const Eigen::Vector3d read =
      ShadowLight::Direction(written["azimuth_deg"].get<double>(), written["elevation_deg"].get<double>());
  EXPECT_LT((read - *found).norm(), 1e-9);
  EXPECT_TRUE(PosesJson(without_run, f.loaded->skeleton(), std::nullopt)["summary"]["shadow_light"].is_null());
}

// One camera, masks that keep the walker's shadow, and a start 900 mm nearer along the
// line of sight (as a start that read the shadow's far end as the feet): the estimate's
// own body covers much of the shadow, so the light is looked for with the body moved
// away along the line of sight as well (Tracker::LookForShadowLight). Oracles: the clip's
// own light, found on the fewest looks there can be (the coarse grid's six and the fine
// grid's six, a look every 2nd frame: frame 22; with the estimate's place alone, frame
// 52), and the root's true place on the floor.
TEST(Tracker, OneCamerasShadowIsFoundWithTheWalkerPlacedTooNear) {
  const Fixture& f = Shared();
  constexpr int kClipFrames = 60;
  ClipOptions clip = SmallClip(kClipFrames);
  clip.rig.num_cameras = 1;
  clip.rig.width = 240, clip.rig.height = 180;
  const ShadowClip shadowed(clip);
  const ClipGroundTruth& truth = shadowed.truth;
  const Eigen::Vector3d& light = shadowed.light;
  TrackerOptions options;
  options.annealing.particles = 150;
  options.shadow.every = 2;
  Tracker tracker(*f.loaded, truth.cameras, options);
  InitialGuess guess = TruthGuess(truth, *f.loaded, tracker.state_model());
  const Eigen::Vector3d eye = truth.cameras[0].CentreInWorld();
  const Eigen::Vector2d toward = (Eigen::Vector2d(eye.x(), eye.z()) - guess.floor_mm).normalized();
  guess.floor_mm += 900 * toward;
  guess.floor_std_mm = 30;
  tracker.StartAt(guess);
  double end_mm = 0;  // the root's floor error over the last 15 frames
  std::string line;
  for (int k = 0; k < kClipFrames; ++k) {
    const TrackedFrame out = tracker.Step(ClipFrameAt(truth, shadowed.clip(), k));
    const Eigen::Vector3d d = out.joints_mm.col(0) - truth.frames[k].joints_mm.col(0);
    if (k % 5 == 0) line += " " + std::to_string(static_cast<int>(std::hypot(d.x(), d.z())));
    if (k >= kClipFrames - 15) end_mm += std::hypot(d.x(), d.z()) / 15;
  }
  const std::optional<Eigen::Vector3d>& found = tracker.shadow_light().light();
  ASSERT_TRUE(found.has_value()) << "root off by (mm):" << line;
  const double off_deg = std::acos(std::clamp(found->dot(light), -1.0, 1.0)) * 180 / std::numbers::pi;
  std::printf("the light found at frame %d, %.1f degrees off; root off by (mm, every 5th frame):%s; %.0f over the "
              "last 15\n", tracker.shadow_light_frame(), off_deg, line.c_str(), end_mm);
  EXPECT_LT(off_deg, 6);
  EXPECT_LE(tracker.shadow_light_frame(), 2 * 12);
  EXPECT_LT(end_mm, 200);
}

// Two cameras whose blobs hold a shadow cast towards them, attached at the feet, and
// one whose blob is the walker alone: the shadowed two read the place too near them and
// agree with each other, and the median of the three readings is theirs. The start tries
// each camera's own reading as well as the median (before, the median alone, with 120 mm
// of spread: on the surveillance quad of the realism suite two cameras' readings a metre
// off, one with a shadow and one with a ball in its blob, outvoted the right one, and the
// first ten frames were tracked 300-800 mm off). Here the second camera of the clip is
// seen twice, shadowed. Oracles: each camera's reading on its own (LocatePerson with that
// camera's mask alone) lies near some place the start tries, and the first frame tracked
// is placed where the truth is: 50 mm off, where the median alone gave 575 (shadows of a
// tenth of the blob's height; 0.06-0.14 gave 8-50 mm against 197-756).
TEST(Tracker, AStartTriesEachCamerasReadingOfThePlace) {
  const Fixture& f = Shared();
  const std::vector<Camera> cameras = {f.truth.cameras[0], f.truth.cameras[1], f.truth.cameras[1]};
  std::vector<Frame> frames;
  for (int k = 0; k < 15; ++k) {
    Frame frame = ClipFrameAt(f.truth, f.clip, k);
    cv::Mat& mask = frame.masks[1];
    const cv::Rect box = cv::boundingRect(mask);
    const int width = std::max(2, box.width / 3), length = box.height / 10;
    const int x = box.x + box.width / 2 - width / 2, y = box.y + box.height - 1;
    mask(cv::Rect(x, y, width, std::min(length, mask.rows - y - 1))).setTo(255);
    frame.masks.push_back(mask.clone());
    frames.push_back(std::move(frame));
  }
  TrackerOptions options;
  options.annealing.particles = 150;
  Tracker tracker(*f.loaded, cameras, options);
  InitialGuess guess;
  ASSERT_TRUE(tracker.Guess(frames, &guess));
  std::vector<Eigen::Vector2d> tried = guess.other_floors_mm;
  tried.push_back(guess.floor_mm);
  for (size_t c = 0; c < cameras.size(); ++c) {
    const PersonSighting alone = LocatePerson({cameras[c]}, {frames[0].masks[c]});
    ASSERT_TRUE(alone.found && alone.feet_seen) << c;
    double nearest = 1e300;
    for (const Eigen::Vector2d& place : tried) nearest = std::min(nearest, (place - alone.floor_mm).norm());
    std::printf("camera %zu's own reading: %.0f mm from the median, %.0f from the nearest place tried\n", c,
                (alone.floor_mm - guess.floor_mm).norm(), nearest);
    EXPECT_LT(nearest, 150) << c;
  }
  const Eigen::Vector3d root = f.truth.frames[0].joints_mm.col(0);
  ASSERT_TRUE(tracker.StartFromFrames(frames));
  const TrackedFrame first = tracker.Step(frames[0]);
  const double placed = std::hypot(first.joints_mm(0, 0) - root.x(), first.joints_mm(2, 0) - root.z());
  std::printf("the median %.0f mm from the walker; the first frame's root %.0f mm off\n",
              std::hypot(guess.floor_mm.x() - root.x(), guess.floor_mm.y() - root.z()), placed);
  EXPECT_LT(placed, 100);
}

// The shared clip's first `count` frames with a shadow drawn from the feet towards camera
// 0 (a strip a third of the blob wide, a quarter of its height long, below it), as on the
// harsh 2-camera clip: camera 0 reads the walker about a metre nearer.
std::vector<Frame> ShadowTowardsCamera0(int count) {
  const Fixture& f = Shared();
  std::vector<Frame> frames;
  for (int k = 0; k < count; ++k) {
    Frame frame = ClipFrameAt(f.truth, f.clip, k);
    cv::Mat& mask = frame.masks[0];
    const cv::Rect box = cv::boundingRect(mask);
    const int width = std::max(2, box.width / 3), y = box.y + box.height;
    mask(cv::Rect(box.x + box.width / 2 - width / 2, y, width, std::min(box.height / 4, mask.rows - 1 - y))).setTo(255);
    frames.push_back(std::move(frame));
  }
  return frames;
}

// One camera of two reads the walker over a metre off along its line of sight (a shadow
// from the feet towards it, ShadowTowardsCamera0), so the locator counts
// the two cameras' blobs as two people and starts from one: where the two lines of sight
// meet (FuseReadings) is among the places the start tries, and the first frame is there.
TEST(Tracker, AStartTriesWhereTwoCamerasLinesOfSightMeet) {
  const Fixture& f = Shared();
  const std::vector<Frame> frames = ShadowTowardsCamera0(5);
  const Eigen::Vector3d root = f.truth.frames[4].joints_mm.col(0);
  const Eigen::Vector2d truth(root.x(), root.z());
  std::vector<Eigen::Vector2d> alone;
  for (size_t c = 0; c < 2; ++c) {
    const PersonSighting s = LocatePerson({f.truth.cameras[c]}, {frames[4].masks[c]});
    ASSERT_TRUE(s.found && s.feet_seen) << c;
    alone.push_back(s.floor_mm);
  }
  ASSERT_GT((alone[0] - alone[1]).norm(), 1000) << "the two cameras' readings must not agree";
  TrackerOptions options;
  options.annealing.particles = 150;
  Tracker tracker(*f.loaded, f.truth.cameras, options);
  InitialGuess guess;
  ASSERT_TRUE(tracker.Guess(frames, &guess));
  double nearest = (guess.floor_mm - truth).norm();
  for (const Eigen::Vector2d& place : guess.other_floors_mm) nearest = std::min(nearest, (place - truth).norm());
  ASSERT_TRUE(tracker.StartFromFrames(frames));
  const TrackedFrame first = tracker.Step(frames[4]);
  const double placed = std::hypot(first.joints_mm(0, 0) - root.x(), first.joints_mm(2, 0) - root.z());
  std::printf("readings %.0f and %.0f mm off; the nearest place tried %.0f mm off; the first frame's root %.0f\n",
              (alone[0] - truth).norm(), (alone[1] - truth).norm(), nearest, placed);
  EXPECT_LT(nearest, 300);
  EXPECT_LT(placed, 150);
}

// The shared clip with a shadow from the feet towards camera 0 in every frame
// (ShadowTowardsCamera0), and the estimate
// started where that camera alone reads the walker: a metre off along its line of sight,
// its drawing on the walker's blob there, off the blob in camera 1. The second looks try
// where the two cameras' lines of sight meet (Tracker::MeetingPlaces), and the estimate
// is brought there at the first (frame 4: 30 mm off over frames 5-14; not tried, the
// silhouettes alone pull it in by frame 14, 600 mm off over them).
TEST(Tracker, AnEstimateOffAlongOneCamerasLineOfSightIsBroughtToWhereTheyMeet) {
  const Fixture& f = Shared();
  const std::vector<Frame> frames = ShadowTowardsCamera0(kFrames);
  const PersonSighting alone = LocatePerson({f.truth.cameras[0]}, {frames[0].masks[0]});
  ASSERT_TRUE(alone.found && alone.feet_seen);
  for (const bool meet : {true, false}) {
    TrackerOptions options;
    options.annealing.particles = 100;
    options.starts_try_each_camera = meet;
    Tracker tracker(*f.loaded, f.truth.cameras, options);
    InitialGuess guess = TruthGuess(f.truth, *f.loaded, tracker.state_model());
    guess.floor_mm = alone.floor_mm, guess.floor_std_mm = 30;
    const double start_off = (guess.floor_mm - f.truth.frames[0].joints_mm.col(0)({0, 2})).norm();
    ASSERT_GT(start_off, 700);
    tracker.StartAt(guess);
    double after = 0;  // the root's mean error over frames 5-14, after the first second look
    std::string line;
    for (int k = 0; k < kFrames; ++k) {
      const TrackedFrame out = tracker.Step(frames[k]);
      ASSERT_TRUE(out.state.size()) << k;
      const Eigen::Vector3d d = out.joints_mm.col(0) - f.truth.frames[k].joints_mm.col(0);
      const double error = std::hypot(d.x(), d.z());
      if (k >= 5 && k < 15) after += error / 10;
      line += " " + std::to_string(static_cast<int>(error));
    }
    std::printf("%s: started %.0f mm off, %.0f over frames 5-14; root off by (mm):%s\n",
                meet ? "where the lines of sight meet tried" : "not tried", start_off, after, line.c_str());
    if (meet) {
      EXPECT_LT(after, 150);
    }
  }
}

// The walker goes behind a painted pillar in one view, bit by bit from frame 25, while the
// other (which they walk towards) is blocked whole, and stays behind it to the end (1.7 s
// hidden). The frames tracked on what is left of them must not turn or slow the walk the
// prediction goes on with: it walks on as the walker was seen going (Tracker::
// WalkOnAsSeen), and is near them when the clip ends (296 mm off; 582 walking on with
// what the slices left, 580 with the heading alone restored).
TEST(Tracker, AWalkerGoingBehindAPillarIsPredictedWalkingOnAsSeen) {
  test::TempDir dir;
  const Walk0701 walk;
  constexpr int kLong = 75, kBehind = 25;
  RenderClip(walk.skeleton, walk.motion, walk.source, {}, SmallClip(kLong), (dir.path() / "clip").string());
  const ClipGroundTruth truth = ReadGroundTruth(dir.path() / "clip/ground_truth.json");
  // Each camera's pillar: the columns from the walker's root at frame kBehind on, on the
  // side they walk towards (all of the view of a camera they walk towards).
  std::vector<cv::Mat> pillars;
  for (const Camera& camera : truth.cameras) {
    Eigen::Vector2d from, to;
    ASSERT_TRUE(camera.Project(truth.frames[kBehind].joints_mm.col(0), &from));
    ASSERT_TRUE(camera.Project(truth.frames[kLong - 1].joints_mm.col(0), &to));
    cv::Mat pillar(camera.height, camera.width, CV_8UC1, cv::Scalar(0));
    const int edge = static_cast<int>(std::lround(from.x()));
    if (std::abs(to.x() - from.x()) < 10) pillar.setTo(255);  // walking along the line of sight: all of it
    else if (to.x() > from.x()) pillar.colRange(std::clamp(edge, 0, camera.width), camera.width).setTo(255);
    else pillar.colRange(0, std::clamp(edge, 0, camera.width)).setTo(255);
    pillars.push_back(pillar);
  }
  const auto tracker = SharedTracker(150, 1, &truth.cameras);
  std::vector<Frame> first;
  for (int k = 0; k < 5; ++k) first.push_back(ClipFrameAt(truth, dir.path() / "clip", k));
  ASSERT_TRUE(tracker->StartFromFrames(first));
  TrackedFrame out;
  for (int k = 0; k < kLong; ++k) {
    Frame frame = ClipFrameAt(truth, dir.path() / "clip", k);
    if (k >= kBehind) {
      for (size_t c = 0; c < frame.masks.size(); ++c) frame.masks[c].setTo(0, pillars[c]);
      frame.hidden = pillars;
    }
    out = tracker->Step(frame);
  }
  const Eigen::Vector3d root = truth.frames[kLong - 1].joints_mm.col(0);
  const double off = std::hypot(out.joints_mm(0, 0) - root.x(), out.joints_mm(2, 0) - root.z());
  std::printf("status at the end %s, root %.0f mm off\n", std::string(TrackStatusName(out.status)).c_str(), off);
  EXPECT_EQ(out.status, TrackStatus::kPredicted);
  EXPECT_LT(off, 400);
}

// Going back over a start (Tracker::BackOver): a second tracker from this one's state at
// the last frame, back to the first, on exact masks of the shared clip. Its estimates
// follow the truth at every frame going back, and this tracker goes on as if it had not
// been asked (its next estimates equal a twin's that never went back).
TEST(Tracker, GoingBackOverFramesFollowsTheWalkAndChangesNothing) {
  const Fixture& f = Shared();
  std::vector<Frame> frames;
  for (int k = 0; k < kFrames; ++k) frames.push_back(ClipFrameAt(f.truth, f.clip, k));
  const int back_from = 15;
  const auto tracker = SharedTracker(100, 4), twin = SharedTracker(100, 4);
  const std::vector<Frame> first(frames.begin(), frames.begin() + 5);
  ASSERT_TRUE(tracker->StartFromFrames(first) && twin->StartFromFrames(first));
  for (int k = 0; k <= back_from; ++k) tracker->Step(frames[k]), twin->Step(frames[k]);
  const std::vector<TrackedFrame> back = tracker->BackOver({frames.begin(), frames.begin() + back_from + 1});
  ASSERT_EQ(back.size(), static_cast<size_t>(back_from));
  double worst = 0;
  for (int k = 0; k < back_from; ++k) {
    ASSERT_EQ(back[k].index, k);
    const Eigen::Vector3d d = back[k].joints_mm.col(0) - f.truth.frames[k].joints_mm.col(0);
    worst = std::max(worst, std::hypot(d.x(), d.z()));
    EXPECT_GT(back[k].state[tracker->state_model().placement().rate], 0) << k;  // walking forwards, as tracked
  }
  std::printf("going back over %d frames: the root at most %.0f mm off\n", back_from, worst);
  EXPECT_LT(worst, kRootBoundMm + 40);
  for (int k = back_from + 1; k < kFrames; ++k) {
    const TrackedFrame a = tracker->Step(frames[k]), b = twin->Step(frames[k]);
    EXPECT_EQ(a.joints_mm, b.joints_mm) << k;
  }
}

// A start sure only later: one camera at head height, the walker's legs hidden (painted)
// for the first 16 frames, so their first places are read from the head alone, which from
// that height hardly tells depth. Gone back over from the last frame (feet seen for 9
// frames), the first frame's place is nearer the truth than the forward pass's.
TEST(Tracker, GoingBackOverAStartPlacesItsFirstFramesFromLaterOnes) {
  const Fixture& f = Shared();
  const Eigen::Vector3d centre = WalkCentre();
  // 4.5 m from the walk, at right angles to it, as the suite's monocular clip.
  const Eigen::Vector3d walk = f.truth.frames.back().joints_mm.col(0) - f.truth.frames.front().joints_mm.col(0);
  const Eigen::Vector3d aside = Eigen::Vector3d(walk.z(), 0, -walk.x()).normalized() * 4500;
  const Camera level = LookAtCamera("cam0", 320, 240, 260, {centre.x() + aside.x(), 1500, centre.z() + aside.z()},
                                    {centre.x(), 1000, centre.z()});
  test::TempDir dir;
  const ClipGroundTruth truth = RenderThrough(level, dir.path());
  std::vector<Frame> frames;
  for (int k = 0; k < kFrames; ++k) {
    frames.push_back(ClipFrameAt(truth, dir.path() / "clip", k));
    if (k > 15) continue;
    cv::Mat& mask = frames.back().masks[0];
    const cv::Rect box = cv::boundingRect(mask);
    frames.back().hidden.push_back(HideFrom(&mask, box.y + box.height * 3 / 4));  // the shins and below
  }
  const auto root_error = [&](const TrackedFrame& estimate) {
    const Eigen::Vector3d d = estimate.joints_mm.col(0) - truth.frames[estimate.index].joints_mm.col(0);
    return std::hypot(d.x(), d.z());
  };
  double forward = 0, backward = 0;
  const int seeds = 4;
  for (int seed = 1; seed <= seeds; ++seed) {
    const std::unique_ptr<Tracker> held = SharedTracker(100, seed, &truth.cameras);
    Tracker& tracker = *held;
    ASSERT_TRUE(tracker.StartFromFrames({frames.begin(), frames.begin() + 15}));
    TrackedFrame at_first;
    for (const Frame& frame : frames) {
      TrackedFrame out = tracker.Step(frame);
      if (frame.index == 0) at_first = std::move(out);
    }
    const std::vector<TrackedFrame> back = tracker.BackOver(frames);
    ASSERT_EQ(back.size(), frames.size() - 1) << seed;
    std::printf("seed %d: the first frame's root %.0f mm off forwards, %.0f gone back over\n", seed,
                root_error(at_first), root_error(back.front()));
    forward += root_error(at_first) / seeds;
    backward += root_error(back.front()) / seeds;
  }
  std::printf("mean %.0f mm forwards, %.0f gone back over\n", forward, backward);
  EXPECT_LT(backward, 0.6 * forward);
}

// A start with the legs the wrong way round (the truth half a walking cycle on), the mirror
// switch off: the other order, tracked alongside for a few frames, explains them better
// and is taken (TrackerOptions::legs_trial_frames). Without the trial the legs stay
// swapped, so the test can fail.
TEST(Tracker, AStartWithTheLegsSwappedIsTurnedByTheOtherOrderTrackedAlongside) {
  const Fixture& f = Shared();
  std::vector<Frame> frames;
  for (int k = 0; k < kFrames; ++k) frames.push_back(ClipFrameAt(f.truth, f.clip, k));
  const int trial = 10, judged_from = trial + 2;
  const auto swapped_share = [&](int trial_frames) {
    TrackerOptions options;
    options.annealing.particles = 150;
    options.annealing.seed = 1;
    options.mirror_margin = 1e9;  // only the trial may turn the legs
    options.legs_trial_frames = trial_frames;
    Tracker tracker(*f.loaded, f.truth.cameras, options);
    InitialGuess guess = TruthGuess(f.truth, *f.loaded, tracker.state_model());
    EXPECT_EQ(guess.coordinates.size(), 3);
    guess.coordinates[0] = std::fmod(guess.coordinates[0] + 0.5, 1.0);
    tracker.StartAt(guess);
    std::vector<Eigen::Matrix3Xd> tracked, truth;
    for (const Frame& frame : frames) {
      const TrackedFrame out = tracker.Step(frame);
      if (frame.index < judged_from) continue;
      tracked.push_back(out.joints_mm);
      truth.push_back(f.truth.frames[frame.index].joints_mm);
    }
    const TrackErrors e =
        CompareTracks(tracked, f.loaded->skeleton().BoneNames(), truth, f.truth.joint_names, Bodytrack14());
    std::printf("the other leg order tried for %d frames: legs swapped in %.0f%% of frames %d-%d, %.1f mm\n",
                trial_frames, 100 * e.swap_rate, judged_from, kFrames - 1, e.absolute_mm);
    return e.swap_rate;
  };
  EXPECT_GT(swapped_share(0), 0.5);
  EXPECT_LT(swapped_share(trial), 0.2);
}

}  // namespace
}  // namespace jgpm
