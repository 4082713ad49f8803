#include "tracker/frames/clip_source.h"

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "io/base/error.h"
#include "io/video/video_file.h"
#include "tracker/clip/mask_png.h"

namespace jgpm {

ClipFrameSource::ClipFrameSource(const std::filesystem::path& folder, const ClipFrameSourceOptions& options)
    : paths_{folder}, options_(options) {
  std::error_code ec;
  if (!std::filesystem::is_directory(folder, ec)) ThrowInputError(folder.string(), "no such clip folder");
  truth_ = ReadGroundTruth(paths_.GroundTruth());
  const int available = static_cast<int>(truth_.cameras.size());
  indices_ = options.cameras;
  if (indices_.empty()) {
    for (int c = 0; c < available; ++c) indices_.push_back(c);
  }
  for (size_t i = 0; i < indices_.size(); ++i) {
    const int c = indices_[i];
    if (c < 0 || c >= available) {
      ThrowInputError(folder.string(), "the clip has " + std::to_string(available) + " camera(s) (0-" +
                                           std::to_string(available - 1) + "), not camera " + std::to_string(c));
    }
    for (size_t k = 0; k < i; ++k)
      if (indices_[k] == c) ThrowInputError(folder.string(), "camera " + std::to_string(c) + " asked for twice");
    cameras_.push_back(truth_.cameras[c]);
  }
  num_frames_ = static_cast<int>(truth_.frames.size());
  if (options.max_frames > 0) num_frames_ = std::min(num_frames_, options.max_frames);
  if (options.foreground) options_.with_images = true;
  if (options_.with_images) {
    for (const Camera& camera : cameras_) {
      const std::filesystem::path video = paths_.Video(camera.name);
      videos_.emplace_back(video.string());
      if (!videos_.back().isOpened()) ThrowInputError(video.string(), "cannot be opened as a video");
    }
  }
  if (options.foreground) {
    for (const Camera& camera : cameras_) {
      extractors_.emplace_back(*options.foreground, camera.width, camera.height);
      const std::filesystem::path plate = paths_.Background(camera.name);
      if (!options.learn_background && std::filesystem::exists(plate, ec)) {
        const cv::Mat image = cv::imread(plate.string(), cv::IMREAD_COLOR);
        if (image.cols != camera.width || image.rows != camera.height) {
          ThrowInputError(plate.string(), "is not a " + std::to_string(camera.width) + "x" +
                                              std::to_string(camera.height) + " image of the empty room");
        }
        extractors_.back().SetBackground(image);
      } else {
        const std::string video = paths_.Video(camera.name).string();
        extractors_.back().Learn(
            VideoFileSource(video, options.foreground->learning_frames).Sample(options.foreground->learning_frames));
      }
    }
  }
}

bool ClipFrameSource::Next(Frame* frame) {
  if (next_ >= num_frames_) return false;
  const int k = next_;
  const ClipFrame& f = truth_.frames[k];
  frame->index = k;
  frame->time_s = f.time_s;
  frame->dropped = f.dropped;
  frame->masks.assign(cameras_.size(), cv::Mat());
  frame->images.assign(options_.with_images ? cameras_.size() : 0, cv::Mat());
  frame->latency_ms = 0;
  ++next_;
  if (f.dropped) return true;
  for (size_t c = 0; c < cameras_.size(); ++c) {
    const Camera& camera = cameras_[c];
    if (options_.with_images) {
      cv::Mat image;
      if (!videos_[c].read(image)) ThrowInputError(paths_.Video(camera.name).string(), "ends before frame " +
                                                                                        std::to_string(frame->index));
      frame->images[c] = image;
    }
    if (!extractors_.empty()) {
      frame->masks[c] = extractors_[c].Apply(frame->images[c]);
      continue;
    }
    const std::filesystem::path path =
        options_.exact_masks ? paths_.Mask(camera.name, k) : paths_.ObservedMask(camera.name, k);
    frame->masks[c] = ReadMaskPng(path, camera.width, camera.height);
  }
  return true;
}

}  // namespace jgpm
