// The frame source a `jgpm track` command line asks for, made in one place: a synthetic
// clip (its masks, or its videos through background subtraction), video files, an image
// folder, or a live V4L2 camera, each camera with its calibration.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "calibration/camera.h"
#include "calibration/camera_guess.h"
#include "tracker/frames/foreground.h"
#include "tracker/frames/frame_source.h"

namespace jgpm {

struct FrameSourceSpec {
  // Exactly one kind of source.
  std::string clip;                 // a synthetic clip folder
  std::vector<std::string> videos;  // video files, one per camera
  std::string images;               // an image folder...
  double images_fps = 0;            // ...and its frame rate
  std::vector<std::string> devices;  // live cameras, /dev/videoN, or fake:VIDEO (a video
                                     // played in real time through the V4L2 code and a
                                     // software camera, io/video/fake_v4l2_device.h: for tests)
  // Cameras: of a clip, the indices to use (empty: all); otherwise one YAML per source,
  // or a guess.
  std::vector<int> clip_cameras;
  std::vector<std::string> camera_yamls;
  std::vector<Camera> cameras;  // or cameras already made (calibrated from the walkers)
  bool camera_guess = false;
  CameraGuess guess;
  // Masks: a clip's exact masks instead of its observed ones; or, when `foreground` is
  // set for a clip, computed from its videos as for any video.
  bool exact_masks = false;
  bool clip_foreground = false;
  bool clip_images = false;  // a clip's videos decoded too, ahead with the masks (for overlays)
  ForegroundOptions foreground;
  std::vector<std::string> backgrounds;
  double mask_person_px = 0;  // VideoFrameSourceOptions::person_px: a learnt background's
                              // masks made at the working resolution
  // Static occluders (occluder_masks.h): a painting per camera; a clip has its own
  // (occluders/, when its scene has any), used unless `clip_occluders` is off.
  std::vector<std::string> occluders;
  bool clip_occluders = true;
  // Each blob's reflection in a glossy floor cut from the masks (floor_reflection.h; not
  // through a guessed camera).
  bool cut_reflections = true;
  // Live camera.
  int device_width = 640, device_height = 480;
  double device_fps = 30;
  std::string device_format = "auto";  // auto, yuyv, mjpg
  int max_frames = 0;
  // Told what a live camera gave and what the start needs (the command prints it).
  std::function<void(const std::string&)> note;
};

// InputError naming the option, file or device for anything unusable: no source or two,
// a video without a camera YAML (the message says how to make one), cameras that do not
// match their sources.
std::unique_ptr<FrameSource> MakeFrameSource(const FrameSourceSpec& spec);

// The paintings of static occluders for the source's cameras (`--occluders`, or the
// clip's own), one per camera, or none at all. InputError naming the option or file: a
// count that is not the cameras', paintings given to a clip, a painting unreadable or of
// another size than its camera's images.
std::vector<cv::Mat> OccluderPaintings(const FrameSourceSpec& spec, const std::vector<Camera>& cameras);

}  // namespace jgpm
