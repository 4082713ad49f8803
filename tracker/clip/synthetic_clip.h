// Synthetic clips: a motion-capture trial rendered through calibrated cameras, with exact
// ground truth, for testing and benchmarking the tracker. The folder's files are described
// in tracker/clip/clip_format.h; the cameras in clip_rig.h; the person in clip_body.h; the
// occluders and the shadow in clip_scene.h; the degradations in clip_degradations.h.
// Without options a clip is today's: the tracker's own body in the lab's ring.
// Several walkers (a crowd clip) share the cameras, the scene and the degradations; each has
// its own motion, body, place on the floor, heading and start time, and the renderer
// draws them together, so they hide one another as people do.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "calibration/camera.h"
#include "io/mocap/motion.h"
#include "io/mocap/skeleton.h"
#include "tracker/clip/clip_body.h"
#include "tracker/clip/clip_degradations.h"
#include "tracker/clip/clip_format.h"
#include "tracker/clip/clip_rig.h"
#include "tracker/clip/clip_scene.h"

namespace jgpm {

struct ClipOptions {
  double fps = 30;             // clip frame rate (at most the motion's); nearest frames
  int max_frames = 0;          // 0: the whole trial
  RigOptions rig;              // used when no cameras are given
  ClipDegradations degradations;
  ClipBodyOptions body;        // who walks, in what
  SceneOptions scene;          // occluders and the shadow
  double calibration_error = 0;  // the written cameras differ from the rendering ones by
                                 // this times a real calibration's error (clip_rig.h)
  // Stops (--pause): every walker stands still at each pause's time of its trial for its
  // length, then walks on; the clip lasts that much longer. People stop and start, mocap
  // trials of walks rarely do, and a walking prior's dynamics assume they never do.
  std::vector<ClipPause> pauses;
  uint64_t seed = 1;           // degradations, noise, rig, scene, calibration error
  bool contact_sheet = true;

  bool Check(std::string* why) const;
};

struct ClipSummary {
  int frames = 0;    // clip frames, dropped included
  int dropped = 0;
  std::vector<Camera> cameras;
  double seconds = 0;
  std::string BriefReport() const;
};

// Where the motion came from, for ground_truth.json.
struct ClipSource {
  std::string asf;
  std::string amc;
};

// One walker of a clip: a motion, the person who makes it, and where and when.
struct ClipWalker {
  Skeleton skeleton;
  Motion motion;
  ClipSource source;
  ClipBodyOptions body;
  // Unplaced: the trial as recorded, starting with the clip. Placed: turned about the
  // vertical and moved so that its middle frame's root is at (at_x_mm, at_z_mm) walking
  // towards heading_deg (its first-to-last root direction; a trial that moves less than
  // 300 mm is only turned by heading_deg), its middle frame shown delay_s after the first
  // walker's. The first walker's delay must be 0: the clip is the first walker's trial
  // (or max_frames of it), and the others enter and leave the scene as their trials begin
  // and end.
  ClipPlacement placement;
};

// The body of walker `index` (from 0) of a clip whose options give `first`'s: the same
// clothing and width scale, another person for each (body seed + index), so that the
// first keeps the body a one-walker clip would have.
ClipBodyOptions WalkerBody(const ClipBodyOptions& first, int index);

// The time into a walker's trial shown `walker_s` seconds after it began, with `pauses`
// (in trial time, any order): a pause holds the trial's time at its start for its length.
double TrialTime(double walker_s, const std::vector<ClipPause>& pauses);

// Renders the clip into `out_dir`, which must not exist or be empty: it is written as
// `<out_dir>.partial` and renamed when complete, so a failure leaves nothing half-made. An
// existing `<out_dir>.partial` (another render writing there, or one that was killed) is
// refused, never removed.
// `cameras` empty: MakeRig. `progress` (may be empty) gets (images done, total).
// InputError for bad options, an invalid camera, two cameras with one name, or an
// unusable output folder.
ClipSummary RenderClip(const Skeleton& skeleton, const Motion& motion, const ClipSource& source,
                       std::vector<Camera> cameras, const ClipOptions& options,
                       const std::string& out_dir,
                       const std::function<void(int, int)>& progress = {});
// Several walkers (1-8; their shapes at most 254 in all, the ray caster's limit); each
// walker's body is its own (options.body is not used). With one walker, the same clip as
// above with options.body = walkers[0].body.
ClipSummary RenderClip(const std::vector<ClipWalker>& walkers, std::vector<Camera> cameras,
                       const ClipOptions& options, const std::string& out_dir,
                       const std::function<void(int, int)>& progress = {});

}  // namespace jgpm
