// `jgpm track` as a library call: read a model and a clip, track every frame, write the
// results folder (tracker/track_output.h) whole or not at all, and measure the run against
// the clip's ground truth.
#pragma once

#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "tracker/clip_format.h"
#include "tracker/track_output.h"
#include "tracker/tracker.h"

namespace jgpm {

struct TrackJobOptions {
  std::string model;               // model file
  std::string asf;                 // the subject's skeleton (ASF), when known: the model's
                                   // poses are placed on it at size 1 (empty: the model's
                                   // own skeleton, scaled to the person's estimated size)
  std::string clip;                // clip folder (tracker/clip_format.h)
  std::string out;                 // results folder; empty: write nothing
  std::vector<int> cameras;        // the clip's cameras to use; empty: all
  bool exact_masks = false;        // the clip's exact masks instead of its observed ones
  int max_frames = 0;              // 0: all
  bool truth_start = false;        // start from the clip's truth (--init truth)
  bool overlays = true;            // overlay videos (decode the clip's videos)
  TrackerOptions tracker;
};

struct TrackJobResult {
  TrackRun run;
  std::optional<RunErrors> errors;           // against the clip's ground truth
  std::vector<std::filesystem::path> written;
};

// InputError naming the file or option for anything unusable, before any output is made.
// `progress` (may be empty) gets each tracked frame and the number of frames.
TrackJobResult RunTrackJob(const TrackJobOptions& options,
                           const std::function<void(const TrackedFrame&, int total)>& progress = {});

// The model with its reference skeleton replaced by the ASF file's (same bones and dofs,
// other lengths); InputError naming the file when the channels do not fit it.
std::unique_ptr<GaitModel> ModelOnSkeleton(const GaitModel& model, const std::string& asf);

// The guess a clip's truth gives at frame 0 for a model's state model: the true root,
// heading and size, and (when the model can say) the state coordinates of the true pose.
InitialGuess TruthGuess(const ClipGroundTruth& truth, const GaitModel& model, const StateModel& state_model);

}  // namespace jgpm
