// How well a body explains the foreground masks: the tracker's likelihood.
//
// Per camera, with S the body's silhouette (tracker/body/bit_silhouette.h), O the observed
// foreground and R the region where the person is expected (foreground elsewhere, such as
// clutter, is ignored):
//   area    ( |S \ grow(O n R)| + |(O n R) \ grow(S)| ) / max(|O n R|, min_foreground_px)
//           both directions: the body outside the mask AND the mask the body leaves
//           unexplained (one direction alone lets legs collapse onto each other, or the
//           body shrink into the mask); grow() adds a pixel all round, so a mask eroded or
//           dilated by a pixel or two (any segmentation's edge) costs little;
//   outline mean over points along the body's outline of the distance (px) to the nearest
//           foreground pixel, truncated and divided by truncation_px: a wide, smooth basin
//           where the overlap is flat (a limb just beside the mask), robust to holes and
//           clutter because it saturates; points beyond the image's edges are left out, as
//           the area term leaves out the body's pixels there (what the image does not show
//           is no evidence either way);
//   raw     area + outline_weight * outline;
//   cost    B (1 - exp(-raw / B)): the raw cost where it is small, never more than B. A camera is a mixture of a working view and a
//           failed one (its segmentation lost the person, a shadow or a coat took over,
//           its calibration is off, something hides the person): the failed view explains
//           any mask at a fixed cost, so no camera's evidence is worth more than that and
//           one camera cannot decide a frame against the others (Sigal's HumanEva
//           baseline bounds each camera's term; a mask the body misses entirely, which
//           raw costs 10-20 against a good view's 0.1-0.5, now costs B).
//           And a body cannot lower its cost by leaving a camera's view: drawing nothing
//           where the camera sees foreground costs B, as much as drawing it anywhere else.
// B's rule: a body drawn where the person is not, beside a person of its size, has raw
// cost 2 + outline_weight (every body pixel outside the mask, every mask pixel
// unexplained, the outline saturated): that is the most a view can say against a
// hypothesis, so B = 2 + outline_weight.
// Cameras add their costs (independent views multiply likelihoods); the filter weighs a
// particle by exp(-beta * cost) with beta set by annealing.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core/mat.hpp>

#include "calibration/camera.h"
#include "tracker/body/bit_silhouette.h"
#include "tracker/body/body_model.h"
#include "tracker/filter/observation.h"

namespace jgpm {

struct LikelihoodOptions {
  double outline_weight = 0.5;     // of the outline term against the area term
  double truncation_px = 10;       // outline distances saturate here
  double outline_step_px = 3;      // outline samples at most this far apart
  double min_foreground_px = 150;  // the area term's normaliser when little is seen
  // Enclosed holes in a mask smaller than this are filled (pixels at 320x240, a walker
  // 80-120 px tall: about a hand's area). On the realism tuning clips (seeds 1-3, mean
  // bodytrack 14 absolute mm) 60 gives 127.5, 30 gives 134.8, 120 gives 130.1.
  int max_hole_px = 60;
  bool bound_cameras = true;       // each camera's cost at most 2 + outline_weight (above)

  bool Check(std::string* why) const;
};

// One camera's part of a cost.
struct CameraScore {
  int model_px = 0;      // |S|
  int model_rows = 0;    // the rows S spans, top to bottom
  int observed_px = 0;   // |O n R|
  int overlap_px = 0;    // |S n O n R|
  int outside_px = 0;    // |S \ grow(O n R)|
  int unexplained_px = 0;  // |(O n R) \ grow(S)|
  double area = 0;
  double outline = 0;
  double raw = 0;        // area + outline_weight * outline
  double cost = 0;       // raw, bounded (the camera's part of the total)
  double Iou() const;    // overlap / union (0 when both are empty)
};

class SilhouetteLikelihood {
 public:
  explicit SilhouetteLikelihood(const std::vector<Camera>& cameras, const LikelihoodOptions& options = {});

  // Scratch for one thread: a blank canvas per camera and the outline points.
  struct Workspace {
    std::vector<BitMask> canvas;
    std::vector<Eigen::Vector2f> outline;
    std::vector<uint64_t> grown_row;
  };
  Workspace NewWorkspace() const;

  // A camera's mask prepared for Cost (distances truncated as the options say), with the
  // region where the person is expected, and where others are drawn (CameraObservation).
  CameraObservation Observe(const cv::Mat& mask, const cv::Rect& region, const cv::Mat& hidden = cv::Mat()) const;

  int NumCameras() const { return static_cast<int>(renderers_.size()); }
  const BitSilhouetteRenderer& renderer(int camera) const { return renderers_[camera]; }
  const LikelihoodOptions& options() const { return options_; }

  // The summed cost of the placed body against one observation per camera; `scores` (may
  // be null) receives each camera's part. Thread-safe with one workspace per thread.
  double Cost(const std::vector<Capsule>& capsules, const std::vector<CameraObservation>& observations,
              Workspace* workspace, std::vector<CameraScore>* scores = nullptr) const;

  // The body's shadow on the floor (y = floor_mm) under a distant light from `light`, drawn
  // with it within each camera's region; none when not given.
  void SetShadow(const std::optional<Eigen::Vector3d>& light, double floor_mm = 0) {
    light_ = light;
    floor_mm_ = floor_mm;
  }
  const std::optional<Eigen::Vector3d>& light() const { return light_; }
  // Cost with the shadow cast from `light` (none when null) instead of the one set.
  double CostUnder(const Eigen::Vector3d* light, const std::vector<Capsule>& capsules,
                   const std::vector<CameraObservation>& observations, Workspace* workspace,
                   std::vector<CameraScore>* scores = nullptr) const;

 private:
  // What camera `camera` shows a body standing at `feet` (FloorPointUnder): with painted
  // objects, the observation with only those in front of it hidden (occluder_layers.h).
  const CameraObservation& Seen(const CameraObservation& observation, const Eigen::Vector3d& feet,
                                size_t camera) const;

  std::vector<BitSilhouetteRenderer> renderers_;
  std::vector<Eigen::Vector3d> centres_;  // each camera's, in the world (mm)
  LikelihoodOptions options_;
  std::optional<Eigen::Vector3d> light_;
  double floor_mm_ = 0;
};

}  // namespace jgpm
