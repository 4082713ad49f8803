// Synthetic clips: a motion-capture trial rendered through calibrated cameras, with exact
// ground truth, for testing and benchmarking the tracker. The folder's files are described
// in tracker/clip/clip_format.h; the cameras in clip_rig.h; the person in clip_body.h; the
// occluders and the shadow in clip_scene.h; the degradations in clip_degradations.h.
// Without options a clip is today's: the tracker's own body in the lab's ring.
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

}  // namespace jgpm
