// What a tracking run leaves for people and tools, written by `jgpm track` into one folder:
//   poses.json          per frame (with --people all: per frame and person, with its id):
//                       status (tracked, predicted, lost), every bone end (mm,
//                       named exactly as a clip's ground_truth.json names them, same world
//                       frame), the root, heading, size, the state's coordinates, effective
//                       sample size and per-camera overlap; errors when the truth is known.
//                       No times: one seed gives one file, with any number of threads
//   tracked.bvh         the motion with its root translation (centimetres), for animation
//   tracked.amc, .asf   the same in Acclaim form, on the model's skeleton scaled by the
//                       person's size
//   overlay_camK.avi    each camera's frames with the estimated silhouette's outline and
//                       skeleton drawn over them
//   track.png           error over time per joint group, when the truth is known
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>
#include <opencv2/core/mat.hpp>

#include "io/base/output_batch.h"
#include "io/mocap/motion.h"
#include "prior/model/gait_model.h"
#include "tracker/filter/multi_tracker.h"
#include "tracker/filter/tracker.h"
#include "tracker/frames/frame_source.h"
#include "tracker/run/mot_metrics.h"
#include "tracker/run/track_metrics.h"

namespace jgpm {

// A finished run and what it ran on.
struct TrackRun {
  std::string model_path;
  std::string source;                    // the clip folder, video, ...
  std::string init = "auto";             // "auto" or "truth"
  std::vector<std::string> coordinate_names;
  std::string state_space;               // "manifold", "latent", "joint-space"
  std::vector<Camera> cameras;
  double fps = 30;
  TrackerOptions options;
  std::vector<TrackedFrame> frames;
  double tracking_seconds = 0;           // filtering only (no decoding, no writing)
  // Per camera, the median over its frames of the share of its masks that is foreground
  // (empty: not measured). A fixed camera's is its people, a few percent.
  std::vector<double> foreground_share;
};

// The errors of a run against per-frame true bone ends (empty matrices: no truth), on the
// 17 gait joints and on the 14 joints of PARSEC bodytrack's measure.
struct RunErrors {
  TrackErrors gait17, bodytrack14;
};
RunErrors EvaluateRun(const TrackRun& run, const Skeleton& skeleton, const std::vector<Eigen::Matrix3Xd>& truth,
                      const std::vector<std::string>& truth_bones);

nlohmann::json PosesJson(const TrackRun& run, const Skeleton& skeleton, const std::optional<RunErrors>& errors);
// Several people (--people all): each frame holds `people`, each with a one-person frame's
// fields and its id, and the ids born and ended there; the summary lists each id's first
// and last frame; CLEAR MOT figures when the truth is known.
nlohmann::json PeoplePosesJson(const TrackRun& run, const Skeleton& skeleton, const std::vector<PeopleFrame>& frames,
                               const std::optional<MotResult>& mot);

// The tracked motion on the model's skeleton scaled by the person's median size (as an ASF
// text, whose `length` unit carries the scale), with the root's translation and heading.
// Frames without an estimate hold the nearest estimate.
struct TrackedMotion {
  std::string asf;
  Skeleton skeleton;
  Motion motion;
};
TrackedMotion MakeTrackedMotion(const TrackRun& run, const GaitModel& model);

// One overlay frame: the image (or grey) with the estimate's silhouette outline, skeleton
// and a status line; once the light of the walkers' shadows is found, the outline of the
// shadow drawn with the body, at half the outline's colour.
cv::Mat OverlayFrame(const cv::Mat& image, const Camera& camera, const TrackedFrame& frame,
                     const std::vector<Capsule>& capsules, const Skeleton& skeleton);

// Several people (jgpm track --people all): each one's outline (and shadow's) in its own
// colour (PersonColour), its skeleton and its id above its head; a line with the frame and how
// many are tracked.
struct OverlayPerson {
  int id = 0;
  TrackedFrame frame;
  std::vector<Capsule> capsules;
};
cv::Mat OverlayPeopleFrame(const cv::Mat& image, const Camera& camera, int index,
                           const std::vector<OverlayPerson>& people, const Skeleton& skeleton);
cv::Scalar PersonColour(int id);  // BGR, distinct for neighbouring ids

// Error over time per joint group (legs, arms, trunk and head), mm.
cv::Mat ErrorPlot(const RunErrors& errors, const TrackRun& run);

}  // namespace jgpm
