// Synthetic clips: a motion-capture trial rendered through calibrated cameras, with exact
// ground truth, for testing and benchmarking the tracker. A clip folder holds
//   ground_truth.json        frame rate, cameras, per frame the time, source frame and
//                            3-D joint positions (mm), and which frames were dropped
//   camK.yaml                each camera (calibration/camera.h YAML)
//   camK.avi                 colour video (MJPG): shaded body over a textured room, noise
//   masks/camK/NNNNNN.png    exact silhouettes (ray cast), one per kept frame
//   observed/camK/NNNNNN.png the silhouettes after the mask degradations (the tracker's
//                            input when it skips background subtraction)
//   contact_sheet.png        frames per camera with the skeleton over the silhouette
// NNNNNN is the clip frame number; dropped frames have no image and no video frame.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "calibration/camera.h"
#include "io/motion.h"
#include "io/skeleton.h"
#include "tracker/body_model.h"

namespace jgpm {

struct RigOptions {
  int num_cameras = 2;             // 1-4: side view, front view, then around the ring
  int width = 320;                 // image size, pixels
  int height = 240;
  double ring_radius_mm = 4500;    // from the walk's centre (grown when the walk is longer)
  double camera_height_mm = 1500;  // above the floor

  bool Check(std::string* why) const;
};

struct ClipDegradations {
  double sensor_noise = 3;     // std of per-pixel Gaussian noise in the video, grey levels
  double mask_noise_px = 0;    // observed masks: each frame eroded or dilated by up to this
  int holes = 0;               // observed masks: holes (radius 2-5 px) punched per frame
  int clutter_blobs = 0;       // coloured blobs moving over the background (video + masks)
  double lighting_gain = 1;    // brightness at the end: ramps from 1 over the middle third
  double drop_rate = 0;        // probability that a frame (not the first) is dropped

  bool Check(std::string* why) const;
  bool Any() const;
};

struct ClipOptions {
  double fps = 30;             // clip frame rate (at most the motion's); nearest frames
  int max_frames = 0;          // 0: the whole trial
  RigOptions rig;              // used when no cameras are given
  ClipDegradations degradations;
  BodyModelOptions body;
  uint64_t seed = 1;           // degradations and noise
  bool contact_sheet = true;

  bool Check(std::string* why) const;
};

// Cameras on a ring about the centre of the walk (the root's path), looking at its middle
// at 1 m height: first the side view (perpendicular to the walking direction), then the
// front view, then the others around the ring (3: 120 degrees apart; 4: every 90). Each
// camera's focal length is the largest that keeps every joint, padded by a body's width,
// inside its image in every frame.
std::vector<Camera> DefaultRig(const std::vector<Eigen::Matrix3Xd>& joint_in_world_mm,
                               const RigOptions& options);

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
// `<out_dir>.partial` and renamed when complete, so a failure leaves nothing half-made.
// `cameras` empty: DefaultRig. `progress` (may be empty) gets (images done, total).
// InputError for bad options, an invalid camera, two cameras with one name, or an
// unusable output folder.
ClipSummary RenderClip(const Skeleton& skeleton, const Motion& motion, const ClipSource& source,
                       std::vector<Camera> cameras, const ClipOptions& options,
                       const std::string& out_dir,
                       const std::function<void(int, int)>& progress = {});

}  // namespace jgpm
