#include "tracker/cli/track_commands.h"

#include <cstdio>
#include <memory>
#include <thread>

#include "io/error.h"
#include "tracker/cli/progress.h"
#include "tracker/track_job.h"

namespace jgpm::cli {
namespace {

struct TrackArguments {
  TrackJobOptions job;
  std::string cameras;
  std::string init = "auto";
  std::string space = "model";
  bool no_latent_prior = false;
  bool no_overlay = false;
  int threads = 0;
};

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

void RunTrack(TrackArguments a) {
  a.job.cameras = ParseCameraList(a.cameras);
  a.job.truth_start = a.init == "truth";
  a.job.overlays = !a.no_overlay;
  a.job.tracker.space = a.space == "joint-space" ? StateSpace::kJointSpace : StateSpace::kModel;
  a.job.tracker.annealing.latent_prior = !a.no_latent_prior;
  a.job.tracker.threads = a.threads > 0 ? a.threads : std::max(1u, std::thread::hardware_concurrency());
  ProgressLine line("track");
  const TrackJobResult result = RunTrackJob(a.job, [&line](const TrackedFrame& f, int total) {
    char detail[96];
    std::snprintf(detail, sizeof(detail), "%-9s ess %.2f  overlap %.2f", std::string(TrackStatusName(f.status)).c_str(),
                  f.ess, f.MeanIou());
    line.Update(f.index + 1, total, "frames", detail);
  });
  line.Finish();
  const TrackRun& run = result.run;
  int tracked = 0, predicted = 0, lost = 0;
  for (const TrackedFrame& f : run.frames) {
    tracked += f.status == TrackStatus::kTracked;
    predicted += f.status == TrackStatus::kPredicted;
    lost += f.status == TrackStatus::kLost;
  }
  const int n = static_cast<int>(run.frames.size());
  std::printf("tracked %d frames (%d tracked, %d predicted, %d lost) of %s with %s (%s space, %d x %d particles x layers, "
              "%s start) at %.1f frames/s\n",
              n, tracked, predicted, lost, run.source.c_str(), run.model_path.c_str(), run.state_space.c_str(),
              run.options.annealing.particles, run.options.annealing.layers, run.init.c_str(),
              run.tracking_seconds > 0 ? n / run.tracking_seconds : 0.0);
  if (result.errors) {
    for (const auto& [name, e] : {std::pair<const char*, const TrackErrors&>{"14 joints (bodytrack)", result.errors->bodytrack14},
                                  {"17 gait joints", result.errors->gait17}}) {
      std::printf("error over %-22s %6.1f mm absolute, %6.1f root-relative, %6.1f Procrustes; %.1f%% frames over 150 mm, "
                  "%.1f%% legs swapped\n",
                  name, e.absolute_mm, e.root_relative_mm, e.procrustes_mm, 100 * e.failure_rate, 100 * e.swap_rate);
    }
  }
  for (const auto& file : result.written) std::printf("wrote %s\n", file.string().c_str());
}

}  // namespace

void AddTrackCommands(CLI::App& app) {
  auto a = std::make_shared<TrackArguments>();
  CLI::App* track = app.add_subcommand("track", "Track a walking person's 3-D pose in a clip with a gait prior");
  track->add_option("--model", a->job.model, "trained gait model (jgpm train)")->required();
  track->add_option("--clip", a->job.clip, "synthetic clip folder (jgpm render)")->required();
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
  track->add_option("--threads", a->threads, "threads (0: all cores)")->check(CLI::Range(0, 256))->capture_default_str();
  track->add_option("--max-frames", a->job.max_frames, "track at most this many frames (0: all)")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  track->add_flag("--exact-masks", a->job.exact_masks, "the clip's exact masks instead of its observed (degraded) ones");
  track->add_flag("--no-overlay", a->no_overlay, "skip the overlay videos");
  track->callback([a] { RunTrack(*a); });
}

}  // namespace jgpm::cli
