// `jgpm bench track`: every clip of the tracking suite tracked with every model (and the
// baselines) in one run, measured against the clips' truth: mean 3-D joint error (absolute,
// root-relative, Procrustes-aligned) on the 14 joints of PARSEC bodytrack's measure and the
// 17 gait joints, with and without the joint-angle refinement, failure and leg-swap rates,
// frames per second of filtering and likelihood evaluations per frame, averaged over seeds.
// Beside each model, its floor: per frame the model's best pose for the true pose (sequence
// inference, prior/model/inference.h, on the true gait poses), root-relative, on the skeleton the
// row tracks on (the subject's own for the known-skeleton runs; otherwise the model's, at
// the size that fits best): tracker error / floor says how much is search and how much
// prior and skeleton.
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include <opencv2/core/mat.hpp>

#include "tracker/clip/tracking_suite.h"
#include "tracker/filter/tracker.h"

namespace jgpm {

// A crowd clip (ground truth with `people`: datasets_scripts/crowd_suite.txt) is tracked
// with --people all only ("people", and "people-from-video" with from_video): the
// one-person methods would follow the first walker alone.
struct TrackBenchOptions {
  std::vector<std::string> models;  // model files
  bool joint_space = true;          // the classic baseline (on the first model's skeleton)
  bool no_latent_prior = true;      // the first model without p(x|M)
  bool known_skeleton = true;       // the first model on the subject's own skeleton (the
                                    // clip's source ASF, as jgpm track --asf)
  bool from_video = true;           // the first model on masks computed from the clip's
                                    // videos by background subtraction, as for a recording
  int seeds = 2;
  int max_frames = 0;               // per clip; 0: all
  TrackerOptions tracker;
};

struct TrackBenchRow {
  std::string clip, model, method;  // method: "prior", "known-skeleton", "no-latent-prior",
                                    // "joint-space", "from-video"
  int cameras = 0, frames = 0, seeds = 0;
  double bt14_mm = 0, bt14_root_mm = 0, bt14_procrustes_mm = 0;   // refined (the output)
  double g17_mm = 0, g17_root_mm = 0, g17_procrustes_mm = 0;
  double search_bt14_mm = 0, search_g17_root_mm = 0;              // before refinement
  double failure_rate = 0, swap_rate = 0, lost_rate = 0;
  // Lost while the person was in view (PersonInView): the share of frames (mean over the
  // seeds) and the longest run (frames, the worst seed). A restart loop shows here; a
  // walker who left every view does not.
  double lost_in_view_rate = 0;
  int longest_lost_in_view = 0;
  double fps = 0, evaluations_per_frame = 0;
  double fps_with_input = 0;  // with reading the frames (and background subtraction)
  double floor_bt14_root_mm = -1, floor_g17_root_mm = -1;         // -1: not applicable
  double triangulated_bt14_mm = -1;  // TriangulatedByWrittenCameras; -1: not applicable
  // The 17 gait joints' absolute error (refined), averaged over the seeds: per joint, and
  // per frame (NaN where a seed had no estimate).
  std::vector<std::string> joints;
  std::vector<double> per_joint_mm, per_frame_mm;
  // Several walkers (a crowd clip, method "people" or "people-from-video": --people all):
  // CLEAR MOT averaged over the seeds (tracker/run/mot_metrics.h), bt14_mm the paired
  // people's error, fps frames (everyone in them) a second. -1 / 0 for one-walker rows.
  int walkers = 0;
  double mota = -1, motp_mm = -1, misses = 0, false_positives = 0, id_switches = 0, fragmentations = 0;
  double people_per_frame = 0, ms_per_person = 0;
};

// The model's best poses for the clip's first `frames` true poses (sequence inference on the
// true gait poses), root-relative mean error (mm) against the truth on the subject's
// skeleton: placed on the subject's skeleton (the floor of a tracker that knows it) and on
// the model's skeleton at the size in the tracker's range that fits best (the floor of one
// that estimates the size alone: CMU skeletons differ in bone directions and axes, so the
// same angles put an arm 60-80 mm elsewhere). -1 when the source trial cannot be read or
// its channels are not the model's.
struct PriorFloors {
  double subject_bt14 = -1, subject_g17 = -1;
  double model_bt14 = -1, model_g17 = -1;
};
PriorFloors ModelFloors(const GaitModel& model, const ClipGroundTruth& truth, int frames);

// What the calibration error of a clip (--calibration-error) does on its own: the true
// joints of the first `frames` frames, seen by the cameras that rendered the images and
// triangulated by the written ones (each joint the least-squares meeting point of the
// written cameras' rays through its true pixels), against the truth; bodytrack's 14
// joints, absolute mm. Triangulation knows nothing else; the tracker also knows that the
// feet are on the floor and how big people are, which can place it closer (the 2-camera
// calibration clip: 127 mm triangulated, 109 tracked). -1 when the written cameras are the
// rendering ones or fewer than two.
double TriangulatedByWrittenCameras(const ClipGroundTruth& truth, int frames);

// Whether the clip's person is in view at `frame`: in the image of some camera that
// rendered the clip (render_cameras when the clip has them) half of the true joints or
// more lie, and, when `clip` is the clip's folder, the person shows there: the exact mask
// (masks/CAMERA) holds at least kShowsArea h^2 pixels, h the true joints' height in that
// image. Rule: a quarter of an unhidden walker's usual area, 0.18 h^2 (the median on the
// tracking suite's exact masks, 0.15-0.18 per clip, the least 0.12). A walker behind a
// pillar is out of view; a dropped frame (no mask) is judged on the joints alone.
inline constexpr double kShowsArea = 0.25 * 0.18;
bool PersonInView(const ClipGroundTruth& truth, int frame, const std::filesystem::path& clip = {});
// Frames with status lost while in view, and the longest such run (`in_view` per frame).
struct LostInView {
  int frames = 0, longest = 0;
};
LostInView CountLostInView(const std::vector<TrackStatus>& status, const std::vector<bool>& in_view);

// Tracks every clip in `folder` (rendered: tracker/clip/tracking_suite.h). `progress` (may be
// empty) gets each finished row with the number done and the total.
std::vector<TrackBenchRow> RunTrackBench(const std::vector<SuiteClip>& clips, const std::filesystem::path& folder,
                                         const TrackBenchOptions& options,
                                         const std::function<void(const TrackBenchRow&, int done, int total)>& progress = {});

std::string TrackBenchCsv(const std::vector<TrackBenchRow>& rows);
// Long tables of the same runs: clip,model,method,joint,mm and clip,model,method,frame,mm.
std::string TrackBenchJointsCsv(const std::vector<TrackBenchRow>& rows);
std::string TrackBenchFramesCsv(const std::vector<TrackBenchRow>& rows);
// Mean absolute error (14 joints) per clip, one bar per model and method.
cv::Mat TrackBenchPlot(const std::vector<TrackBenchRow>& rows);

// The accuracy-versus-budget curve: one clip tracked at each particles x layers budget.
struct BudgetPoint {
  int particles = 0, layers = 0;
  double bt14_mm = 0, fps = 0;
};
std::vector<BudgetPoint> RunBudgetCurve(const std::filesystem::path& clip, const std::string& model,
                                        const std::vector<std::pair<int, int>>& budgets, const TrackBenchOptions& options);
// Error against frames per second, with PARSEC bodytrack's published points on the same clip
// (../shared/docs/TRACKER.md) for comparison.
cv::Mat BudgetPlot(const std::vector<BudgetPoint>& points, const std::string& clip);

}  // namespace jgpm
