#include "tracker/cli/walker_video.h"

#include <algorithm>
#include <filesystem>

#include <opencv2/core.hpp>

#include "io/base/error.h"
#include "io/cli/progress.h"
#include "tracker/frames/foreground.h"
#include "tracker/frames/frame_source_factory.h"
#include "tracker/frames/walker_points.h"

namespace jgpm::cli {

WalkerEvidence ReadWalkersFromVideo(const WalkerVideo& video) {
  constexpr int kLiveFrames = 900;
  FrameSourceSpec spec;
  bool live = false;
  if (std::filesystem::exists(std::filesystem::path(video.video) / "ground_truth.json")) {
    spec.clip = video.video;  // a synthetic clip's observed masks
  } else if (std::filesystem::is_directory(video.video)) {
    if (!(video.fps > 0)) ThrowInputError("--walkers " + video.video, "a folder of frames: give its frame rate with --fps");
    spec.images = video.video;
    spec.images_fps = video.fps;
    spec.camera_guess = true;
  } else if (video.video.rfind("/dev/video", 0) == 0 || video.video.rfind("fake:", 0) == 0) {
    spec.devices = {video.video};  // a live camera, for its next max_frames frames
    if (video.fps > 0) spec.device_fps = video.fps;
    if (video.width > 0 && video.height > 0) spec.device_width = video.width, spec.device_height = video.height;
    spec.camera_guess = true;
    live = true;
  } else {
    spec.videos = {video.video};
    spec.camera_guess = true;  // the masks need no camera; the source wants one
  }
  if (!video.background.empty()) spec.backgrounds = {video.background};
  // A live camera is watched for 30 s at 30 fps unless told otherwise.
  spec.max_frames = live && video.max_frames == 0 ? kLiveFrames : video.max_frames;
  // People far from a surveillance camera are 30-60 px tall with limbs 2-3 px wide, and
  // a head's top or a foot's tip is a pixel or two: the tracker's clean-up (an opening of
  // 1 px radius) trims them. Heads and feet need the whole blob: no opening (specks are
  // dropped by size and shape anyway). The tracker's closing of 1 px.
  spec.foreground.open_px = 0;
  const std::unique_ptr<FrameSource> source = MakeFrameSource(spec);
  const Camera& camera = source->cameras().front();
  WalkerPointFinder finder(camera.width, camera.height);
  ProgressLine line("walkers", 0.5);
  const int total = live ? spec.max_frames : source->NumFrames();
  Frame frame;
  ForegroundShare share;
  while (source->Next(&frame)) {
    if (frame.dropped) {
      finder.Skip();  // keeps the frame numbers on the video's clock
      continue;
    }
    const cv::Mat& mask = frame.masks.front();
    finder.Add(mask);
    share.Add(mask);
    line.Update(live ? finder.frames() : frame.index + 1, total, "frames", "finding heads and feet");
  }
  line.Finish();
  WalkerEvidence evidence;
  evidence.width = camera.width;
  evidence.height = camera.height;
  evidence.frames = finder.frames();
  evidence.fps = source->fps();
  evidence.points = finder.Points();
  evidence.foreground_share = share.Median();
  return evidence;
}

}  // namespace jgpm::cli
