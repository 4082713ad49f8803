// Cameras that deliver colour images (video files, image folders, live V4L2 cameras) as a
// frame source: each image becomes a foreground mask (tracker/frames/foreground.h), and the
// cameras' images are paired by time.
//
// Pairing: the first camera sets the frames; every other camera contributes its image
// nearest in time (its video's time plus its camera's clock_offset_s), if that is within
// half of the first camera's frame period (a frame
// seen by every camera within 17 ms at 30 fps). A frame for which some camera has no such
// image is handed out as dropped (the tracker predicts it rather than read one camera's
// missing view as nobody there), and counted in unpaired().
#pragma once

#include <chrono>
#include <deque>
#include <memory>
#include <string>
#include <vector>

#include "io/video/image_source.h"
#include "tracker/frames/foreground.h"
#include "tracker/frames/frame_source.h"

namespace jgpm {

struct VideoFrameSourceOptions {
  ForegroundOptions foreground;
  std::vector<std::string> backgrounds;  // per camera an empty-scene image; empty: learn it
  int max_frames = 0;                    // 0: all
  // > 0: when the background is learnt from a file or folder, and the people moving in its
  // learning images are taller than this (MovingPersonHeight), each image is brought down to where they are
  // this tall before background subtraction (working_resolution.h's rule, its person_px),
  // and the masks come at that size (mask_scale): subtracting at full size cost 2-3 times
  // the tracking at 720x1280. A live camera, or a given background, stays full size.
  double person_px = 0;
};

class VideoFrameSource : public FrameSource {
 public:
  // One camera per source, same order. InputError naming the source or file: a camera
  // whose image size is not its source's, a background image that is missing or of
  // another size. Learns each camera's background: files and folders here, live cameras
  // from their first learning frames at the first Next (they start streaming then); those
  // frames are then handed out first, tracked like the rest (a person in view from the
  // start is tracked from the start, the background learnt around them).
  VideoFrameSource(std::vector<std::unique_ptr<ImageSource>> sources, std::vector<Camera> cameras,
                   const VideoFrameSourceOptions& options);

  const std::vector<Camera>& cameras() const override { return cameras_; }
  double fps() const override { return sources_[0]->fps(); }
  int NumFrames() const override;
  double mask_scale(size_t camera) const override { return camera < mask_scales_.size() ? mask_scales_[camera] : 1; }
  bool Next(Frame* frame) override;

  bool live() const { return sources_[0]->live(); }
  // Frames lost on the way in all sources (undecodable, or dropped by a live camera).
  int skipped() const;
  int unpaired() const { return unpaired_; }
  // Why a live source stopped early ("" when none did).
  std::string end_reason() const;
  const ImageSource& source(int k) const { return *sources_[k]; }

 private:
  std::vector<std::unique_ptr<ImageSource>> sources_;
  std::vector<Camera> cameras_;
  VideoFrameSourceOptions options_;
  void Learn();  // the live cameras' backgrounds, and every camera's extractor
  std::vector<double> mask_scales_;  // per camera (1: full size)
  std::vector<cv::Size> mask_sizes_;

  std::vector<ForegroundExtractor> foreground_;
  std::vector<std::vector<cv::Mat>> learning_;  // per camera, until learnt
  bool learnt_ = false;
  std::vector<std::deque<Image>> queued_;  // per camera: images read ahead, not yet paired
  struct Kept {
    Image image;
    std::chrono::steady_clock::time_point read;
  };
  std::vector<std::deque<Kept>> replay_;  // per live camera: the learning images, to track
  // The next image of camera c: a kept learning image first, then the source's.
  bool ReadImage(size_t c, Image* image);
  std::vector<bool> finished_;
  int handed_out_ = 0;
  int unpaired_ = 0;
};

}  // namespace jgpm
