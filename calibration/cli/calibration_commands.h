// `jgpm calibrate`: a camera's intrinsics from chessboard images and, optionally, its
// place in the world (from a chessboard on the floor or a pose file), as camera YAML; or,
// with `--walkers VIDEO`, the whole camera from the people walking in a video
// (calibration/walker_calibration.h).
#pragma once

#include <functional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "calibration/walker_calibration.h"

namespace jgpm::cli {

// What `calibrate --walkers` needs from a video: its walkers' head-foot points. Finding
// people in video (background subtraction) is the tracker's layer, above this one, so the
// command is handed the reader (tracker/cli/walker_video.h) by main.cc.
struct WalkerVideo {
  std::string video;       // a video file, a folder of frames, or a synthetic clip folder
  std::string background;  // empty-scene image, or empty: learnt from the video
  int max_frames = 0;      // 0: all
  double fps = 0;          // a folder of frames' rate, or the rate to ask a live camera for
  int width = 0, height = 0;  // the size to ask a live camera for (0: its default)
};
// A fixed camera's foreground is its people: a few percent of the image (a walker a metre
// from a webcam, 10%; the suites' clips 15% at most in any frame). Most of it, most of the
// time (the median over frames above this share), is a camera that moves, cuts between
// shots or changing light (a film's scene, Debian's opencv-doc `Megamind.avi`: 54%).
// `calibrate --walkers` refuses such a video; `track` says so.
constexpr double kMovingCameraShare = 0.25;

struct WalkerEvidence {
  int width = 0, height = 0;  // the video's frame size
  int frames = 0;
  double fps = 0;
  std::vector<HeadFoot> points;
  double foreground_share = 0;  // the median over frames of the share of the image that is
                                // foreground (a moving camera makes most of it so)
};
using ReadWalkers = std::function<WalkerEvidence(const WalkerVideo&)>;

// The cameras from the walkers in their videos (`calibrate --walkers`, `track
// --calibrate-from-walkers`), printing what was found and each number's uncertainty. Each
// take is one video per camera, started within max_clock_offset_s of each other; several
// takes of one camera are several videos of it. One camera is placed above the world
// origin looking along +z; several are each calibrated, then placed in cam0's world from
// the walkers they share (calibration/rig_placement.h). InputError as
// CalibrateFromWalkers and PlaceRig, or naming a video of another size than its camera's
// others.
struct WalkerRequest {
  std::vector<std::vector<std::string>> takes;  // [take][camera]
  std::vector<std::string> backgrounds;         // per camera, or none
  int max_frames = 0;
  double person_height_m = 1.70;
  std::vector<std::string> intrinsics;  // per camera, YAML whose intrinsics to keep, or none
  double fps = 0;                       // of folders of frames; asked of a live camera
  int width = 0, height = 0;            // asked of a live camera (0: its default)
  // Several cameras: how far apart their videos' starts may be, seconds (0: together).
  // Each camera's offset is found with its placement (one per camera, shared by its
  // takes) and kept as its Camera::clock_offset_s.
  double max_clock_offset_s = 2;
};
std::vector<Camera> CalibrateFromWalkerVideos(const WalkerRequest& request, const ReadWalkers& read_walkers);

// Registers `calibrate` under `app`.
void AddCalibrationCommands(CLI::App& app, ReadWalkers read_walkers);

}  // namespace jgpm::cli
