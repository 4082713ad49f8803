// `jgpm track` as a library call: read a model and a frame source (a clip, videos, an
// image folder, a live camera), track every frame, write the results folder
// (tracker/run/track_output.h) whole or not at all, and measure the run against a clip's
// ground truth.
//
// A run that is stopped (Ctrl-C, the time limit, a camera unplugged) still writes what it
// tracked; a run that fails on bad input writes nothing.
#pragma once

#include <atomic>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "tracker/clip/clip_format.h"
#include "tracker/filter/multi_tracker.h"
#include "tracker/filter/tracker.h"
#include "tracker/frames/frame_source_factory.h"
#include "tracker/frames/working_resolution.h"
#include "tracker/run/mot_metrics.h"
#include "tracker/run/track_output.h"

namespace jgpm {

struct TrackJobOptions {
  std::string model;               // model file
  std::string asf;                 // the subject's skeleton (ASF), when known: the model's
                                   // poses are placed on it at size 1 (empty: the model's
                                   // own skeleton, scaled to the person's estimated size)
  FrameSourceSpec source;          // where the frames come from
  std::string out;                 // results folder; empty: write nothing
  bool truth_start = false;        // start from the clip's truth (--init truth)
  bool overlays = true;            // overlay videos (a clip's videos are decoded for them)
  bool save_masks = false;         // OUT/masks/CAMERA/NNNNNN.png: the masks tracked
  double max_seconds = 0;          // stop after this much wall time (0: no limit)
  const std::atomic<bool>* stop = nullptr;  // when it turns true (Ctrl-C): stop, and write
  // Each frame's overlay images as they are made (a live window), when set.
  std::function<void(const std::vector<cv::Mat>& overlays)> show;
  TrackerOptions tracker;
  WorkingResolutionOptions working;  // masks brought down to the working resolution
  // Everyone in view (--people all), each with an id: tracker/filter/multi_tracker.h. The
  // outputs are poses.json with each frame's people, tracked_ID.bvh per person and
  // overlays with each person in their colour; `tracker` is every person's.
  bool people = false;
  MultiTrackerOptions multi;
};

struct TrackJobResult {
  TrackRun run;                              // one person (run.frames empty with --people all)
  std::optional<RunErrors> errors;           // against the clip's ground truth
  std::vector<PeopleFrame> people;           // --people all: each frame's people
  std::optional<MotResult> mot;              // ...against the clip's walkers
  std::optional<TrackErrors> matched_bodytrack14;  // ...the paired people's pose error
  std::vector<std::filesystem::path> written;
  std::string stopped;  // why the run ended before its source did; "" when it did not
  int skipped = 0;      // frames the source lost (undecodable; a live camera's drops)
  int unpaired = 0;     // frames not seen by every camera, predicted
  bool live = false;
  double loop_seconds = 0;  // the tracking loop's wall time: reading and preparing the
                            // frames (decoding, background subtraction) and tracking,
                            // without writing outputs (run.tracking_seconds: filtering)
  double wall_seconds = 0;  // the whole job: reading the model, the pose table, opening
                            // the sources, the loop and writing everything
  double mean_latency_ms = 0, max_latency_ms = 0;  // live: capture to estimate, after the
                                                   // frames held for the start
  int latency_frames = 0;                          // ...over this many frames (0: none)
  int held_frames = 0;  // live: the first frames, left out of the latency (the start's, and
                        // the background's learning frames when it is learnt)
  std::vector<Camera> working_cameras;  // each camera as the tracker saw it (the working
                                        // resolution's; run.cameras are the full-size ones)
  int reflection_frames = 0;  // frames with a reflection in the floor cut from some mask
  // The walker's shadow found in the masks: its light's azimuth and elevation (degrees,
  // ShadowLight::Direction's) and the frame it was found at; none when not found.
  std::optional<Eigen::Vector2d> shadow_light_deg;
  int shadow_light_frame = -1;
};

// Each tracked frame as it is given; the frames the tracker has read so far (a start's
// frames are given after it has read on, so progress is counted in these); the number of
// frames (-1: live); and the frames the source has lost so far (a live camera's drops).
using TrackProgress = std::function<void(const TrackedFrame& frame, int read, int total, int skipped)>;

// InputError naming the file or option for anything unusable, before any output is made.
TrackJobResult RunTrackJob(const TrackJobOptions& options, const TrackProgress& progress = {});

// The model with its reference skeleton replaced by the ASF file's (same bones and dofs,
// other lengths); InputError naming the file when the channels do not fit it.
std::unique_ptr<GaitModel> ModelOnSkeleton(const GaitModel& model, const std::string& asf);

// The guess a clip's truth gives at frame 0 for a model's state model: the true root,
// heading and size, and (when the model can say) the state coordinates of the true pose.
InitialGuess TruthGuess(const ClipGroundTruth& truth, const GaitModel& model, const StateModel& state_model);

}  // namespace jgpm
