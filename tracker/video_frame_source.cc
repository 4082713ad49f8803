#include "tracker/video_frame_source.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include <opencv2/imgcodecs.hpp>

#include "io/error.h"

namespace jgpm {

VideoFrameSource::VideoFrameSource(std::vector<std::unique_ptr<ImageSource>> sources, std::vector<Camera> cameras,
                                   const VideoFrameSourceOptions& options)
    : sources_(std::move(sources)), cameras_(std::move(cameras)), options_(options) {
  JGPM_CHECK(!sources_.empty() && sources_.size() == cameras_.size());
  if (!options.backgrounds.empty() && options.backgrounds.size() != sources_.size()) {
    ThrowInputError("--background", "give one empty-scene image per camera (" + std::to_string(sources_.size()) +
                                        "), or none to learn the scene from the images");
  }
  for (size_t c = 0; c < sources_.size(); ++c) {
    const ImageSource& s = *sources_[c];
    const Camera& camera = cameras_[c];
    if (s.width() != camera.width || s.height() != camera.height) {
      ThrowInputError(s.name(), "is " + std::to_string(s.width()) + "x" + std::to_string(s.height()) + " but its camera " +
                                    camera.name + " is calibrated for " + std::to_string(camera.width) + "x" +
                                    std::to_string(camera.height) + " (give the camera YAML made for this video)");
    }
    foreground_.emplace_back(options.foreground, camera.width, camera.height);
  }
  for (size_t c = 0; c < sources_.size(); ++c) {
    ImageSource& s = *sources_[c];
    if (!options.backgrounds.empty()) {
      const std::string& path = options.backgrounds[c];
      const cv::Mat background = cv::imread(path, cv::IMREAD_COLOR);
      if (background.empty()) ThrowInputError(path, "is not an image OpenCV can read (expected the empty scene)");
      if (background.cols != s.width() || background.rows != s.height()) {
        ThrowInputError(path, "is " + std::to_string(background.cols) + "x" + std::to_string(background.rows) +
                                  ", not the size of " + s.name());
      }
      foreground_[c].SetBackground(background);
      continue;
    }
    std::vector<cv::Mat> learning = s.Sample(options.foreground.learning_frames);
    Image image;
    while (learning.empty() || (s.live() && static_cast<int>(learning.size()) < options.foreground.learning_frames)) {
      if (!s.Read(&image)) break;
      learning.push_back(image.bgr.clone());
    }
    if (learning.empty()) ThrowInputError(s.name(), "gave no image to learn the background from");
    foreground_[c].Learn(learning);
  }
  queued_.resize(sources_.size());
  finished_.assign(sources_.size(), false);
}

int VideoFrameSource::NumFrames() const {
  const int n = sources_[0]->NumFrames();
  if (n < 0) return options_.max_frames > 0 ? options_.max_frames : -1;
  return options_.max_frames > 0 ? std::min(n, options_.max_frames) : n;
}

int VideoFrameSource::skipped() const {
  int n = 0;
  for (const auto& s : sources_) n += s->skipped();
  return n;
}

std::string VideoFrameSource::ended() const {
  for (const auto& s : sources_)
    if (!s->ended().empty()) return s->ended();
  return "";
}

bool VideoFrameSource::Next(Frame* frame) {
  if (options_.max_frames > 0 && handed_out_ >= options_.max_frames) return false;
  Image first;
  if (!sources_[0]->Read(&first)) return false;
  const auto handed = std::chrono::steady_clock::now();
  const size_t n = sources_.size();
  frame->index = first.index;
  frame->time_s = first.time_s;
  frame->latency_ms = first.latency_ms;
  frame->dropped = false;
  frame->images.assign(n, cv::Mat());
  frame->masks.assign(n, cv::Mat());
  frame->images[0] = first.bgr;
  const double tolerance = 0.5 / sources_[0]->fps();
  for (size_t c = 1; c < n; ++c) {
    // Queue this camera's images up to the first one past the tolerance, forget those
    // before it, and take the nearest within it.
    std::deque<Image>& queue = queued_[c];
    while (!finished_[c] && (queue.empty() || queue.back().time_s <= first.time_s + tolerance)) {
      Image image;
      if (!sources_[c]->Read(&image)) {
        finished_[c] = true;
      } else {
        queue.push_back(std::move(image));
      }
    }
    while (!queue.empty() && queue.front().time_s < first.time_s - tolerance) queue.pop_front();
    int best = -1;
    for (int i = 0; i < static_cast<int>(queue.size()) && queue[i].time_s <= first.time_s + tolerance; ++i) {
      if (best < 0 || std::abs(queue[i].time_s - first.time_s) < std::abs(queue[best].time_s - first.time_s)) best = i;
    }
    if (best < 0) {
      frame->dropped = true;
      continue;
    }
    frame->images[c] = queue[best].bgr;
    frame->latency_ms = std::max(frame->latency_ms, queue[best].latency_ms);
    queue.erase(queue.begin(), queue.begin() + best + 1);
  }
  ++handed_out_;
  if (frame->dropped) {
    ++unpaired_;
    for (cv::Mat& image : frame->images) image = cv::Mat();
    return true;
  }
  for (size_t c = 0; c < n; ++c) frame->masks[c] = foreground_[c].Apply(frame->images[c]);
  // Latency counts the foreground too: it is part of getting from capture to an estimate.
  frame->latency_ms += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - handed).count();
  return true;
}

}  // namespace jgpm
