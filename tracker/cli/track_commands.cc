#include "tracker/cli/track_commands.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <set>
#include <thread>

#include <opencv2/highgui.hpp>

#include "calibration/cli/calibration_commands.h"
#include "io/base/error.h"
#include "io/base/output_batch.h"
#include "io/base/png_file.h"
#include "io/cli/device_commands.h"
#include "io/cli/process_clock.h"
#include "io/cli/progress.h"
#include "io/gait/data_root.h"
#include "tracker/cli/walker_video.h"
#include "tracker/clip/tracking_suite.h"
#include "tracker/run/track_bench.h"
#include "tracker/run/track_job.h"

namespace jgpm::cli {
namespace {

struct TrackArguments {
  TrackJobOptions job;
  std::string cameras;
  std::string init = "auto";
  std::string space = "model";
  std::string adapt = "none";
  std::string foreground;  // "" : a clip's masks, or mog2 for other sources
  std::string size;        // a live camera's WxH
  bool no_latent_prior = false;
  bool no_body_shape = false;
  bool no_back_over = false;
  bool no_legs_trial = false;
  bool no_shadow = false;
  bool full_body = false;
  bool no_overlay = false;
  bool show = false;
  int threads = 0;
  bool calibrate_from_walkers = false;
  bool full_resolution = false;
  bool no_clip_occluders = false;
  bool keep_reflections = false;
  double person_height_m = 1.70;
  double max_clock_offset_s = 2;
  double calibration_seconds = 30;
  std::string person = "auto";
  std::string people = "one";
};

// The first Ctrl-C (or SIGTERM) ends tracking and what was tracked is written; the
// handler then steps aside so that a second one kills the process.
std::atomic<bool> interrupted{false};
extern "C" void OnTrackInterrupt(int signal) {
  interrupted = true;
  std::signal(signal, SIG_DFL);
}

// --show: a window per camera when there is a display, else a note.
std::function<void(const std::vector<cv::Mat>&)> LiveWindows() {
  const char* x = std::getenv("DISPLAY");
  const char* wayland = std::getenv("WAYLAND_DISPLAY");
  if ((!x || !*x) && (!wayland || !*wayland)) {
    std::fprintf(stderr, "jgpm: --show: no display (DISPLAY is not set); the overlays are written to --out instead\n");
    return {};
  }
  return [](const std::vector<cv::Mat>& overlays) {
    for (size_t c = 0; c < overlays.size(); ++c) cv::imshow("jgpm track: camera " + std::to_string(c), overlays[c]);
    cv::waitKey(1);
  };
}

// "0,2" -> {0, 2}.
std::vector<int> ParseCameraList(const std::string& text) {
  std::vector<int> cameras;
  size_t start = 0;
  while (start <= text.size() && !text.empty()) {
    const size_t comma = text.find(',', start);
    const std::string item = text.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    char* end = nullptr;
    const long value = std::strtol(item.c_str(), &end, 10);
    if (item.empty() || *end != '\0' || value < 0 || value > 64) {
      ThrowInputError("--cameras " + text, "expected camera indices separated by commas, e.g. 0,2");
    }
    cameras.push_back(static_cast<int>(value));
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return cameras;
}

// --person: "auto" or "U,V" (a pixel of the first camera's full-size image).
PersonPreference ParsePersonOption(const std::string& text) {
  PersonPreference person;
  if (text == "auto") return person;
  const size_t comma = text.find(',');
  double u = 0, v = 0;
  char* end = nullptr;
  bool ok = comma != std::string::npos;
  if (ok) {
    const std::string first = text.substr(0, comma), second = text.substr(comma + 1);
    u = std::strtod(first.c_str(), &end);
    ok = !first.empty() && *end == '\0';
    v = std::strtod(second.c_str(), &end);
    ok = ok && !second.empty() && *end == '\0' && std::isfinite(u) && std::isfinite(v) && u >= 0 && v >= 0;
  }
  if (!ok) ThrowInputError("--person " + text, "expected auto or a pixel X,Y of the first camera, e.g. 320,240");
  person.kind = PersonPreference::Kind::kNearPixel;
  person.pixel = Eigen::Vector2d(u, v);
  return person;
}

void RunTrack(TrackArguments a) {
  FrameSourceSpec& spec = a.job.source;
  if (!a.cameras.empty()) spec.clip_cameras = ParseCameraList(a.cameras);
  a.job.tracker.person = ParsePersonOption(a.person);
  a.job.people = a.people == "all";
  if (a.job.people && a.person != "auto") ThrowInputError("--person", "chooses one person; --people all takes everyone");
  if (!a.size.empty()) ParseSizeOption(a.size, &spec.device_width, &spec.device_height);
  spec.clip_foreground = !spec.clip.empty() && !a.foreground.empty();
  spec.foreground.method = a.foreground == "knn" ? ForegroundMethod::kKnn : ForegroundMethod::kMog2;
  if (!spec.images.empty() && spec.images_fps <= 0) ThrowInputError("--images", "give the folder's frame rate with --fps");
  a.job.truth_start = a.init == "truth";
  a.job.overlays = !a.no_overlay;
  a.job.tracker.space = a.space == "joint-space" ? StateSpace::kJointSpace : StateSpace::kModel;
  a.job.tracker.refinement.adapt_posture = a.adapt == "posture";
  a.job.tracker.annealing.latent_prior = !a.no_latent_prior;
  a.job.tracker.shape.enabled = !a.no_body_shape;
  if (a.no_back_over) a.job.tracker.start_backwards_s = 0;
  if (a.no_legs_trial) a.job.tracker.legs_trial_frames = 0;
  a.job.tracker.shadow.enabled = !a.no_shadow;
  if (a.full_body) a.job.tracker.body_detail = BodyDetail::kFull;
  a.job.working.enabled = !a.full_resolution;
  a.job.source.clip_occluders = !a.no_clip_occluders;
  a.job.source.cut_reflections = !a.keep_reflections;
  a.job.tracker.threads = a.threads > 0 ? a.threads : std::max(1u, std::thread::hardware_concurrency());
  if (a.show) a.job.show = LiveWindows();
  if (a.calibrate_from_walkers) {
    if (!spec.images.empty() || (spec.videos.empty() && spec.devices.size() != 1)) {
      ThrowInputError("--calibrate-from-walkers", "calibrates from --video files (one per camera) or "
                                                  "one --device");
    }
    WalkerRequest request;
    request.takes = {spec.videos};
    if (!spec.devices.empty()) {
      // A live camera: its first seconds, then tracking from where it is then.
      request.takes = {spec.devices};
      request.max_frames = std::max(1, static_cast<int>(std::lround(a.calibration_seconds * spec.device_fps)));
      request.fps = spec.device_fps;
      request.width = spec.device_width;
      request.height = spec.device_height;
    }
    request.backgrounds = spec.backgrounds;
    request.person_height_m = a.person_height_m;
    request.max_clock_offset_s = a.max_clock_offset_s;
    spec.cameras = CalibrateFromWalkerVideos(request, ReadWalkersFromVideo);
  }
  spec.note = [](const std::string& text) {
    std::fprintf(stderr, "jgpm: %s\n", text.c_str());
  };
  ProgressLine line("track");
  interrupted = false;
  a.job.stop = &interrupted;
  std::signal(SIGINT, OnTrackInterrupt);
  std::signal(SIGTERM, OnTrackInterrupt);
  const bool people = a.job.people;
  const TrackJobResult result = RunTrackJob(a.job, [&line, people](const TrackedFrame& f, int read, int total, int skipped) {
    char detail[160];
    // With --people all the frame is a summary: tracked when anyone in it is.
    int n = people ? std::snprintf(detail, sizeof(detail), "%s", f.status == TrackStatus::kTracked ? "someone tracked" : "nobody tracked")
                   : std::snprintf(detail, sizeof(detail), "%-9s ess %.2f  overlap %.2f",
                                   std::string(TrackStatusName(f.status)).c_str(), f.ess, f.MeanIou());
    if (total < 0) std::snprintf(detail + n, sizeof(detail) - n, "  latency %.0f ms  dropped %d", f.latency_ms, skipped);
    line.Update(read, total, "frames", detail);
  });
  std::signal(SIGINT, SIG_DFL);
  std::signal(SIGTERM, SIG_DFL);
  line.Finish();
  const TrackRun& run = result.run;
  int tracked = 0, predicted = 0, lost = 0;
  for (const TrackedFrame& f : run.frames) {
    tracked += f.status == TrackStatus::kTracked;
    predicted += f.status == TrackStatus::kPredicted;
    lost += f.status == TrackStatus::kLost;
  }
  const int n = static_cast<int>(a.job.people ? result.people.size() : run.frames.size());
  if (a.job.people) {
    std::set<int> ids;
    long person_frames = 0;
    for (const PeopleFrame& f : result.people) {
      person_frames += static_cast<long>(f.people.size());
      for (const PersonFrame& p : f.people) ids.insert(p.id);
    }
    std::printf("tracked %d frames of %s with %s: %zu people, %.2f a frame on average, at %.1f frames/s (%.1f ms a "
                "person a frame)\n",
                n, run.source.c_str(), run.model_path.c_str(), ids.size(), n ? static_cast<double>(person_frames) / n : 0.0,
                run.tracking_seconds > 0 ? n / run.tracking_seconds : 0.0,
                person_frames ? 1000 * run.tracking_seconds / person_frames : 0.0);
  } else {
    std::printf("tracked %d frames (%d tracked, %d predicted, %d lost) of %s with %s (%s space, %d x %d particles x "
                "layers, %s start) at %.1f frames/s\n",
                n, tracked, predicted, lost, run.source.c_str(), run.model_path.c_str(), run.state_space.c_str(),
                run.options.annealing.particles, run.options.annealing.layers, run.init.c_str(),
                run.tracking_seconds > 0 ? n / run.tracking_seconds : 0.0);
  }
  for (size_t c = 0; c < run.foreground_share.size(); ++c) {
    if (run.foreground_share[c] <= kMovingCameraShare) continue;
    std::printf("warning: %s's masks are %.0f%% foreground in half its frames or more, where a fixed camera's are its "
                "people, a few percent: a moving camera, cuts between shots or changing light? jgpm tracks people "
                "from fixed cameras; these poses are not to be trusted\n",
                run.cameras[c].name.c_str(), 100 * run.foreground_share[c]);
  }
  std::string working;
  for (size_t c = 0; c < run.cameras.size() && c < result.working_cameras.size(); ++c) {
    const Camera& w = result.working_cameras[c];
    if (w.width == run.cameras[c].width && w.height == run.cameras[c].height) continue;
    working += " " + w.name + " " + std::to_string(w.width) + "x" + std::to_string(w.height);
  }
  if (!working.empty()) {
    std::printf("working resolution (people brought to about %.0f px tall):%s\n", a.job.working.person_px,
                working.c_str());
  }
  if (result.reflection_frames > 0) {
    std::printf("reflections in the floor cut from the masks in %d frames (--keep-reflections to keep them)\n",
                result.reflection_frames);
  }
  if (result.shadow_light_deg) {
    std::printf("the masks hold the walkers' shadows: a light from azimuth %.0f, %.0f degrees up, found at frame %d "
                "and drawn with every body since (--no-shadow: neither)\n",
                result.shadow_light_deg->x(), result.shadow_light_deg->y(), result.shadow_light_frame);
  }
  std::printf("with reading the frames%s: %.1f frames/s\n",
              a.job.source.clip.empty() || a.job.source.clip_foreground ? " and background subtraction" : "",
              result.loop_seconds > 0 ? n / result.loop_seconds : 0.0);
  // From the process's start: the libraries' loading is part of what the user waits for.
  const double whole = SecondsSinceProcessStarted().value_or(result.wall_seconds);
  std::printf("the whole run: %.1f s of wall time for %.1f s of tracking (%.2fx: starting jgpm, reading the model and "
              "its pose table, decoding, background subtraction and writing the outputs; %.1f s from reading the "
              "model on)\n",
              whole, run.tracking_seconds, run.tracking_seconds > 0 ? whole / run.tracking_seconds : 0.0,
              result.wall_seconds);
  if (result.mot) {
    const MotResult& m = *result.mot;
    std::printf("CLEAR MOT against the clip's %d walkers (paired within 500 mm on the floor): MOTA %.3f, MOTP %.0f mm; "
                "%d misses, %d false positives, %d identity switches, %d fragmentations over %d true person-frames\n",
                m.truth_tracks, m.mota, m.motp_mm, m.misses, m.false_positives, m.id_switches, m.fragmentations, m.truth);
    if (result.matched_bodytrack14)
      std::printf("error of the paired people over 14 joints (bodytrack) %.1f mm absolute, %.1f root-relative, %.1f "
                  "Procrustes\n",
                  result.matched_bodytrack14->absolute_mm, result.matched_bodytrack14->root_relative_mm,
                  result.matched_bodytrack14->procrustes_mm);
  }
  if (result.errors) {
    for (const auto& [name, e] : {std::pair<const char*, const TrackErrors&>{"14 joints (bodytrack)", result.errors->bodytrack14},
                                  {"17 gait joints", result.errors->gait17}}) {
      std::printf("error over %-22s %6.1f mm absolute, %6.1f root-relative, %6.1f Procrustes; %.1f%% frames over 150 mm, "
                  "%.1f%% legs swapped\n",
                  name, e.absolute_mm, e.root_relative_mm, e.procrustes_mm, 100 * e.failure_rate, 100 * e.swap_rate);
    }
  }
  if (result.live && result.latency_frames == 0) {
    std::printf("live: no latency measured (no frame came after the %d frames the start holds); %d frames dropped by "
                "the camera\n",
                result.held_frames, result.skipped);
  } else if (result.live) {
    std::printf("live: latency from capture to estimate %.1f ms mean, %.1f ms worst over %d frames (after the %d "
                "frames the start holds); %d frames dropped by the camera (processing slower than capture)\n",
                result.mean_latency_ms, result.max_latency_ms, result.latency_frames, result.held_frames,
                result.skipped);
  } else if (result.skipped > 0) {
    std::printf("%d frame(s) of the video did not decode and were skipped\n", result.skipped);
  }
  if (result.unpaired > 0) std::printf("%d frame(s) not seen by every camera were predicted\n", result.unpaired);
  if (!result.stopped.empty()) std::printf("stopped early: %s; what was tracked is written\n", result.stopped.c_str());
  for (const auto& file : result.written) std::printf("wrote %s\n", file.string().c_str());
}

struct BenchArguments {
  std::string suite = std::string(JGPM_SOURCE_DIR) + "/datasets_scripts/tracking_suite.txt";
  std::string out;
  std::string clips;
  std::string data;
  std::string budget_clip = "07_01-4cam";
  int budget_seeds = 4;
  std::vector<std::string> baselines = {"joint-space", "no-latent-prior", "known-skeleton", "from-video"};
  bool no_budget = false;
  bool no_body_shape = false;
  bool no_back_over = false;
  bool no_legs_trial = false;
  bool no_shadow = false;
  bool full_body = false;
  int threads = 0;
  std::string adapt = "none";
  TrackBenchOptions bench;
};

void RunBench(BenchArguments a) {
  if (a.bench.models.empty()) ThrowInputError("--model", "give at least one model file");
  const std::vector<SuiteClip> clips = ReadTrackingSuite(a.suite);
  const std::filesystem::path clip_folder = a.clips.empty() ? std::filesystem::path(a.out) / "clips" : std::filesystem::path(a.clips);
  const auto asked = [&a](const char* name) { return std::find(a.baselines.begin(), a.baselines.end(), name) != a.baselines.end(); };
  a.bench.joint_space = asked("joint-space");
  a.bench.no_latent_prior = asked("no-latent-prior");
  a.bench.known_skeleton = asked("known-skeleton");
  a.bench.from_video = asked("from-video");
  a.bench.tracker.threads = a.threads > 0 ? a.threads : std::max(1u, std::thread::hardware_concurrency());
  a.bench.tracker.refinement.adapt_posture = a.adapt == "posture";
  a.bench.tracker.shape.enabled = !a.no_body_shape;
  if (a.no_back_over) a.bench.tracker.start_backwards_s = 0;
  if (a.no_legs_trial) a.bench.tracker.legs_trial_frames = 0;
  a.bench.tracker.shadow.enabled = !a.no_shadow;
  if (a.full_body) a.bench.tracker.body_detail = BodyDetail::kFull;
  {
    std::error_code ec;
    std::filesystem::create_directories(a.out, ec);
    if (ec) ThrowInputError("--out " + a.out, "cannot create the folder (" + ec.message() + ")");
    const auto root = [&a] { return ResolveDataRoot(a.data.empty() ? std::nullopt : std::optional(a.data)); };
    RenderTrackingSuite(clips, root, clip_folder, [](const SuiteClip& clip, bool rendered) {
      std::printf("%s %s\n", rendered ? "rendered" : "reusing", clip.name.c_str());
      std::fflush(stdout);
    });
  }
  ProgressLine line("bench", 0);
  const std::vector<TrackBenchRow> rows =
      RunTrackBench(clips, clip_folder, a.bench, [&line](const TrackBenchRow& r, int done, int total) {
        line.Finish();
        if (r.walkers > 0) {
          std::printf("%-28s %-13s %-17s %d walkers: MOTA %.3f, MOTP %4.0f mm, %4.1f misses, %4.1f false, %3.1f switches, "
                      "%3.1f fragmentations | paired 14 joints %5.1f mm | %.2f people a frame, %5.1f frames/s (%.1f ms a "
                      "person)\n",
                      r.clip.c_str(), r.model.c_str(), r.method.c_str(), r.walkers, r.mota, r.motp_mm, r.misses,
                      r.false_positives, r.id_switches, r.fragmentations, r.bt14_mm, r.people_per_frame, r.fps,
                      r.ms_per_person);
          std::fflush(stdout);
          line.Update(done, total, "runs");
          return;
        }
        std::printf("%-20s %-13s %-15s 14 joints %5.1f mm | 17 joints root-relative %5.1f, search alone %5.1f, "
                    "floor %5.1f | %4.1f%% failed, %4.1f%% swapped, %4.1f%% lost in view (longest %d) | %5.1f frames/s "
                    "(%5.1f with input)\n",
                    r.clip.c_str(), r.model.c_str(), r.method.c_str(), r.bt14_mm, r.g17_root_mm, r.search_g17_root_mm,
                    r.floor_g17_root_mm, 100 * r.failure_rate, 100 * r.swap_rate, 100 * r.lost_in_view_rate,
                    r.longest_lost_in_view, r.fps, r.fps_with_input);
        if (r.triangulated_bt14_mm >= 0)
          std::printf("%-20s   the written cameras triangulate the true joints %.1f mm from the truth (14 joints): "
                      "what the calibration error alone costs a triangulation\n",
                      r.clip.c_str(), r.triangulated_bt14_mm);
        std::fflush(stdout);
        line.Update(done, total, "runs");
      });
  line.Finish();
  OutputBatch batch;
  const std::filesystem::path out(a.out);
  batch.Add(out / "track.csv", TrackBenchCsv(rows));
  batch.Add(out / "joints.csv", TrackBenchJointsCsv(rows));
  batch.Add(out / "frames.csv", TrackBenchFramesCsv(rows));
  batch.Add(out / "track.png", EncodePng(TrackBenchPlot(rows), "track.png"));
  if (!a.no_budget && std::filesystem::exists(clip_folder / a.budget_clip / "ground_truth.json")) {
    const std::vector<std::pair<int, int>> budgets = {{50, 2}, {50, 3}, {100, 3}, {100, 4}, {200, 4}, {400, 4}, {800, 4}, {1600, 5}};
    TrackBenchOptions budget_options = a.bench;
    budget_options.seeds = a.budget_seeds;  // single swaps move one seed's mean by tens of mm
    const std::vector<BudgetPoint> points =
        RunBudgetCurve(clip_folder / a.budget_clip, a.bench.models[0], budgets, budget_options);
    std::string csv = "clip,model,particles,layers,bt14_mm,fps\n";
    for (const BudgetPoint& p : points) {
      char row[256];
      std::snprintf(row, sizeof(row), "%s,%s,%d,%d,%.2f,%.2f\n", a.budget_clip.c_str(),
                    std::filesystem::path(a.bench.models[0]).stem().string().c_str(), p.particles, p.layers, p.bt14_mm,
                    p.fps);
      csv += row;
      std::printf("budget %4d x %d: %6.1f mm at %6.1f frames/s\n", p.particles, p.layers, p.bt14_mm, p.fps);
    }
    batch.Add(out / "budget.csv", csv);
    batch.Add(out / "budget.png", EncodePng(BudgetPlot(points, a.budget_clip), "budget.png"));
  }
  for (const auto& file : batch.Commit()) std::printf("wrote %s\n", file.string().c_str());
}

}  // namespace

// Shared by `track` and `bench track`.
constexpr const char* kNoBackOverHelp =
    "do not go back over each start, or with --people all each birth (its first second tracked again "
    "backwards once the track is sure: Tracker::BackOver); its frames then cost one pass and are given out as "
    "they come";
constexpr const char* kNoLegsTrialHelp =
    "do not give each start's other leg order a trial (tracked alongside for 10 frames from the particles half "
    "a walking cycle on, taken when it fits better: TrackerOptions::legs_trial_frames)";
constexpr const char* kNoShadowHelp =
    "do not look for the walker's shadow in the masks (a segmentation without shadow removal keeps it), nor "
    "draw it with each body once its light is found (tracker/filter/shadow_light.h)";
constexpr const char* kFullBodyHelp =
    "draw all 30 parts of the body model for every particle, as clips are rendered, instead of the "
    "tracker's 25 (each hand and the neck one part: BodyDetail::kTracking in body_model.h)";
constexpr const char* kAdaptHelp =
    "none: the refinement starts from a running mean of its deviations; posture: the person's posture offset is "
    "a state under the training subjects' posture prior (measured no better on the suite)";

void AddTrackCommands(CLI::App& app) {
  auto a = std::make_shared<TrackArguments>();
  CLI::App* track = app.add_subcommand("track", "Track a walking person's 3-D pose in a clip with a gait prior");
  track->add_option("--model", a->job.model, "trained gait model (jgpm train)")->required();
  // Where the frames come from: exactly one of these.
  track->add_option("--clip", a->job.source.clip, "synthetic clip folder (jgpm render)");
  track->add_option("--video", a->job.source.videos, "video file, one per camera (repeat), each with a --camera")
      ->check(CLI::ExistingFile);
  track->add_option("--images", a->job.source.images, "folder of frames (PNG/JPEG, name order), with --fps");
  track->add_option("--fps", a->job.source.images_fps, "the image folder's frame rate");
  track->add_option("--device", a->job.source.devices,
                    "live V4L2 camera, /dev/videoN (see jgpm devices; repeat for several); fake:VIDEO plays a video "
                    "through the same code in real time");
  CLI::Option* camera =
      track->add_option("--camera", a->job.source.camera_yamls, "calibrated camera YAML per video/images/device source "
                                                                "(jgpm calibrate; repeat, same order)")
          ->check(CLI::ExistingFile);
  CLI::Option* from_walkers = track->add_flag(
      "--calibrate-from-walkers", a->calibrate_from_walkers,
      "no calibration: the camera from the people walking in the --video, first, or in the --device's first "
      "--calibration-seconds (jgpm calibrate --walkers; written to OUT/cam0.yaml); several --video files (cameras "
      "started within --max-clock-offset of each other): each calibrated, then placed from the walkers they share, "
      "the offsets found pairing their frames");
  from_walkers->excludes(camera);
  track->add_option("--calibration-seconds", a->calibration_seconds,
                    "with --calibrate-from-walkers and a --device: how long to watch the walkers before tracking")
      ->check(CLI::Range(1.0, 3600.0))
      ->needs(from_walkers)
      ->capture_default_str();
  track->add_option("--person-height", a->person_height_m, "with --calibrate-from-walkers: the walkers' mean height, m")
      ->check(CLI::Range(1.0, 2.5))
      ->needs(from_walkers)
      ->capture_default_str();
  track->add_option("--max-clock-offset", a->max_clock_offset_s,
                    "with --calibrate-from-walkers and several videos: how far apart they may have started, seconds "
                    "(0: together); the offsets found pair their frames")
      ->check(CLI::Range(0.0, 60.0))
      ->needs(from_walkers)
      ->capture_default_str();
  track->add_flag("--camera-guess", a->job.source.camera_guess,
                  "no calibration: a camera from the image size, --guess-fov, placed --guess-height above the floor "
                  "and tilted --guess-tilt down (rough 3-D)")
      ->excludes(from_walkers);
  track->add_option("--guess-fov", a->job.source.guess.fov_deg, "horizontal field of view, degrees")
      ->check(CLI::Range(10.0, 170.0))
      ->capture_default_str();
  track->add_option("--guess-height", a->job.source.guess.height_mm, "camera height above the floor, mm")
      ->check(CLI::Range(100.0, 10000.0))
      ->capture_default_str();
  track->add_option("--guess-tilt", a->job.source.guess.tilt_deg, "downward tilt, degrees")
      ->check(CLI::Range(-45.0, 80.0))
      ->capture_default_str();
  // Foreground.
  track->add_option("--foreground", a->foreground,
                    "background subtraction: mog2 or knn (default mog2 for videos, images and cameras; for a clip, "
                    "computes its masks from its videos instead of reading them)")
      ->check(CLI::IsMember({"mog2", "knn"}));
  track->add_option("--background", a->job.source.backgrounds,
                    "empty-scene image per camera (repeat; default: learnt from the frames)")
      ->check(CLI::ExistingFile);
  track->add_option("--learning-frames", a->job.source.foreground.learning_frames,
                    "frames the background is learnt from: spread over a file, the first ones of a live camera "
                    "(keep out of view meanwhile)")
      ->check(CLI::Range(1, 10000))
      ->capture_default_str();
  track->add_option("--occluders", a->job.source.occluders,
                    "painting of the static objects in front of where people walk, per camera (repeat; PNG of the "
                    "camera's size, 255 where an object is; tracker/frames/occluder_masks.h)")
      ->check(CLI::ExistingFile);
  track->add_flag("--no-occluders", a->no_clip_occluders,
                  "leave out a clip's own paintings of its occluders (occluders/CAMERA.png)");
  track->add_flag("--keep-reflections", a->keep_reflections,
                  "leave reflections in a glossy floor in the masks (default: each blob's mirror image below its "
                  "feet is cut, by the camera; tracker/frames/floor_reflection.h)");
  track->add_flag("--full-resolution", a->full_resolution,
                  "track at the input's resolution (default: people taller than 200 px are brought to 200 px, "
                  "tracker/frames/working_resolution.h)");
  track->add_flag("--save-masks", a->job.save_masks, "also write the masks tracked, OUT/masks/CAMERA/NNNNNN.png");
  // Live camera.
  track->add_option("--size", a->size, "camera image size asked for, WxH (the nearest the device offers is used)")
      ->capture_default_str();
  track->add_option("--device-fps", a->job.source.device_fps, "camera frame rate asked for")
      ->check(CLI::Range(1.0, 240.0))
      ->capture_default_str();
  track->add_option("--pixel-format", a->job.source.device_format, "auto (YUYV if offered, else MJPG), yuyv or mjpg")
      ->check(CLI::IsMember({"auto", "yuyv", "mjpg"}))
      ->capture_default_str();
  track->add_option("--max-seconds", a->job.max_seconds, "stop after this long and write what was tracked (0: no limit)")
      ->check(CLI::NonNegativeNumber);
  track->add_flag("--show", a->show, "show the overlays live in a window (when there is a display)");
  track->add_option("--person", a->person,
                    "who, when several people are in view: auto (of those in the first frame, the one seen in most "
                    "of the start's frames) or X,Y (the one nearest that pixel of the first camera's first frame); "
                    "kept by the tracker's prediction")
      ->capture_default_str();
  track->add_option("--people", a->people,
                    "one (the person --person chooses) or all: everyone in view, each with an id, born when a new "
                    "person-sized walker appears and ended when they leave (poses.json lists each frame's people, "
                    "tracked_ID.bvh per person)")
      ->check(CLI::IsMember({"one", "all"}))->capture_default_str();
  track->add_option("--max-people", a->job.multi.max_people, "with --people all: at most this many at once")
      ->check(CLI::Range(1, 32))->capture_default_str();
  track->add_option("--asf", a->job.asf, "the subject's skeleton, when known: poses are placed on it (size not estimated)")
      ->check(CLI::ExistingFile);
  track->add_option("--out", a->job.out, "new (or empty) folder for poses.json, tracked.bvh/.amc, overlays, track.png")
      ->required();
  track->add_option("--cameras", a->cameras, "the clip's cameras to use, e.g. 0,2 (default: all)");
  track->add_option("--particles", a->job.tracker.annealing.particles, "particles per layer")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  track->add_option("--layers", a->job.tracker.annealing.layers, "annealing layers per frame")
      ->check(CLI::Range(1, 50))
      ->capture_default_str();
  track->add_option("--seed", a->job.tracker.annealing.seed, "random seed")->capture_default_str();
  track->add_option("--init", a->init, "auto: from the masks; truth: from the clip's ground truth (labelled)")
      ->check(CLI::IsMember({"auto", "truth"}))
      ->capture_default_str();
  track->add_option("--space", a->space, "model: the prior's manifold or latent space; joint-space: the baseline")
      ->check(CLI::IsMember({"model", "joint-space"}))
      ->capture_default_str();
  track->add_flag("--no-latent-prior", a->no_latent_prior, "do not weigh particles by p(x|M)");
  track->add_flag("--no-body-shape", a->no_body_shape, "the model's build: do not learn each region's width, the limbs' lengths and the floor's height (body_shape.h)");
  track->add_flag("--no-back-over", a->no_back_over, kNoBackOverHelp);
  track->add_flag("--no-legs-trial", a->no_legs_trial, kNoLegsTrialHelp);
  track->add_flag("--no-shadow", a->no_shadow, kNoShadowHelp);
  track->add_flag("--full-body", a->full_body, kFullBodyHelp);
  track->add_option("--adapt", a->adapt, kAdaptHelp)->check(CLI::IsMember({"none", "posture"}))->capture_default_str();
  track->add_option("--threads", a->threads, "threads (0: all cores)")->check(CLI::Range(0, 256))->capture_default_str();
  track->add_option("--max-frames", a->job.source.max_frames, "track at most this many frames (0: all)")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  track->add_flag("--exact-masks", a->job.source.exact_masks, "the clip's exact masks instead of its observed (degraded) ones");
  track->add_flag("--no-overlay", a->no_overlay, "skip the overlay videos");
  track->callback([a] { RunTrack(*a); });

}

void AddTrackBench(CLI::App* bench) {
  auto b = std::make_shared<BenchArguments>();
  CLI::App* track_bench = bench->add_subcommand(
      "track", "Track every clip of the tracking suite with every model and the baselines; track.csv and plots");
  track_bench->add_option("--suite", b->suite, "the suite (NAME TRIAL [render options] per line)")->capture_default_str();
  track_bench->add_option("--model", b->bench.models, "model file (repeat for several)")->required();
  track_bench->add_option("--out", b->out, "folder for track.csv, joints.csv, frames.csv, track.png, budget.csv, budget.png")->required();
  track_bench->add_option("--clips", b->clips, "where the suite's clips are rendered or found (default: OUT/clips)");
  track_bench->add_option("--data", b->data, "data root (default: $JGPM_DATA, ./data/cmu, ../shared/data/cmu)");
  track_bench->add_option("--seeds", b->bench.seeds, "runs per clip and method (seeds 1..N), averaged")
      ->check(CLI::Range(1, 100))
      ->capture_default_str();
  track_bench->add_option("--particles", b->bench.tracker.annealing.particles, "particles per layer")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  track_bench->add_option("--layers", b->bench.tracker.annealing.layers, "annealing layers")
      ->check(CLI::Range(1, 50))
      ->capture_default_str();
  track_bench->add_option("--max-frames", b->bench.max_frames, "frames per clip (0: all)")->check(CLI::NonNegativeNumber);
  track_bench->add_option("--threads", b->threads, "threads (0: all cores)")->check(CLI::Range(0, 256));
  track_bench->add_option("--adapt", b->adapt, kAdaptHelp)->check(CLI::IsMember({"none", "posture"}))->capture_default_str();
  track_bench->add_option("--budget-clip", b->budget_clip, "the clip of the accuracy-versus-budget curve")
      ->capture_default_str();
  track_bench->add_option("--baseline", b->baselines,
                          "runs beside the models (repeat; 'none' for none): joint-space (no learned prior), "
                          "no-latent-prior, known-skeleton (the first model on the subject's own ASF), "
                          "from-video (the first model on masks from the clip's videos by background subtraction)")
      ->check(CLI::IsMember({"joint-space", "no-latent-prior", "known-skeleton", "from-video", "none"}))
      ->capture_default_str();
  track_bench->add_option("--budget-seeds", b->budget_seeds, "runs per budget (seeds 1..N), averaged")
      ->check(CLI::Range(1, 100))
      ->capture_default_str();
  track_bench->add_flag("--no-budget", b->no_budget, "skip the budget curve");
  track_bench->add_flag("--no-body-shape", b->no_body_shape, "the model's build: do not learn each region's width, the limbs' lengths and the floor's height (body_shape.h)");
  track_bench->add_flag("--no-back-over", b->no_back_over, kNoBackOverHelp);
  track_bench->add_flag("--no-legs-trial", b->no_legs_trial, kNoLegsTrialHelp);
  track_bench->add_flag("--no-shadow", b->no_shadow, kNoShadowHelp);
  track_bench->add_flag("--full-body", b->full_body, kFullBodyHelp);
  track_bench->callback([b] { RunBench(*b); });
}

}  // namespace jgpm::cli
