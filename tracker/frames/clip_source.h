// A synthetic clip folder (tracker/clip/clip_format.h) as a frame source: its cameras, each
// frame's observed masks (or the exact ones, or masks computed from its videos by
// background subtraction, as a real video's would be) and, when asked, its video frames.
// The clip's ground truth stays available for evaluation and `--init truth`.
#pragma once

#include <filesystem>
#include <memory>
#include <optional>
#include <vector>

#include <opencv2/videoio.hpp>

#include "tracker/clip/clip_format.h"
#include "tracker/frames/foreground.h"
#include "tracker/frames/frame_source.h"

namespace jgpm {

struct ClipFrameSourceOptions {
  std::vector<int> cameras;   // indices into the clip's cameras; empty: all
  bool exact_masks = false;   // masks/ (the exact silhouettes) instead of observed/
  bool with_images = false;   // also decode each camera's video
  // Masks from each camera's video by this background subtraction (tracker/frames/foreground.h),
  // instead of the clip's mask files; started from the clip's picture of the empty room
  // when it has one and `learn_background` is off, else learnt from the video.
  std::optional<ForegroundOptions> foreground;
  bool learn_background = false;
  int max_frames = 0;         // 0: all
};

class ClipFrameSource : public FrameSource {
 public:
  // InputError naming the folder or file: no ground_truth.json, a camera index the clip
  // does not have, a camera YAML that differs from the ground truth's camera.
  ClipFrameSource(const std::filesystem::path& folder, const ClipFrameSourceOptions& options);

  const std::vector<Camera>& cameras() const override { return cameras_; }
  double fps() const override { return truth_.fps; }
  int NumFrames() const override { return num_frames_; }
  // InputError naming the mask file when one is missing or not a readable image of the
  // camera's size.
  bool Next(Frame* frame) override;

  const ClipGroundTruth& truth() const { return truth_; }
  const std::vector<int>& camera_indices() const { return indices_; }

 private:
  ClipPaths paths_;
  ClipFrameSourceOptions options_;
  ClipGroundTruth truth_;
  std::vector<int> indices_;
  std::vector<Camera> cameras_;
  std::vector<cv::VideoCapture> videos_;
  std::vector<ForegroundExtractor> extractors_;
  int num_frames_ = 0;
  int next_ = 0;
};

}  // namespace jgpm
