#include "tracker/frames/video_frame_source.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include <opencv2/core/utility.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "io/base/error.h"
#include "tracker/frames/working_resolution.h"

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
  // Each camera's background: given, or learnt. Files and folders are sampled over their
  // whole length; live cameras give their next frames, all cameras in turn, so that they
  // learn over the same seconds.
  learning_.resize(sources_.size());
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
    } else if (!s.live()) {
      learning_[c] = s.Sample(options.foreground.learning_frames);
      if (learning_[c].empty()) ThrowInputError(s.name(), "gave no image to learn the background from");
    }
  }
  learnt_ = !options.backgrounds.empty();
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

std::string VideoFrameSource::end_reason() const {
  for (const auto& s : sources_)
    if (!s->end_reason().empty()) return s->end_reason();
  return "";
}

void VideoFrameSource::Learn() {
  replay_.resize(sources_.size());
  for (int k = 0; k < options_.foreground.learning_frames; ++k) {
    for (size_t c = 0; c < sources_.size(); ++c) {
      Image image;
      if (sources_[c]->live() && sources_[c]->Read(&image)) {
        image.bgr = image.bgr.clone();
        learning_[c].push_back(image.bgr);
        replay_[c].push_back({std::move(image), std::chrono::steady_clock::now()});
      }
    }
  }
  mask_scales_.assign(sources_.size(), 1.0);
  mask_sizes_.assign(sources_.size(), cv::Size());
  for (size_t c = 0; c < sources_.size(); ++c) {
    if (learning_[c].empty()) ThrowInputError(sources_[c]->name(), "gave no image to learn the background from");
    // People taller than person_px: the images and their moving regions brought down to
    // the working size first (the regions by nearest pixel: they are coarse, found at no
    // more than 600 rows and grown by 2% of the height, and finding them again there cost
    // as much as the medians).
    std::vector<cv::Mat> moving;
    if (options_.person_px > 0 && !sources_[c]->live() && learning_[c].size() >= 10) {
      moving = MovingRegions(learning_[c], options_.foreground.min_area);
    }
    const int tallest = MovingPersonHeight(moving);
    if (tallest > options_.person_px) {
      mask_scales_[c] = options_.person_px / tallest;
      const Camera scaled = ScaleCamera(cameras_[c], mask_scales_[c]);
      mask_sizes_[c] = cv::Size(scaled.width, scaled.height);
      std::vector<cv::Mat>& images = learning_[c];
      cv::parallel_for_(cv::Range(0, static_cast<int>(images.size())), [&](const cv::Range& range) {
        for (int k = range.start; k < range.end; ++k) {
          cv::resize(images[k], images[k], mask_sizes_[c], 0, 0, cv::INTER_AREA);
          cv::resize(moving[k], moving[k], mask_sizes_[c], 0, 0, cv::INTER_NEAREST);
        }
      });
      foreground_[c] = ForegroundExtractor(options_.foreground, scaled.width, scaled.height);
    }
    foreground_[c].Learn(learning_[c], moving);
  }
  learning_.clear();
  learnt_ = true;
}

bool VideoFrameSource::ReadImage(size_t c, Image* image) {
  if (c < replay_.size() && !replay_[c].empty()) {
    // A learning image, tracked after all: its latency includes its wait.
    *image = std::move(replay_[c].front().image);
    image->latency_ms += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() -
                                                                   replay_[c].front().read).count();
    replay_[c].pop_front();
  } else if (!sources_[c]->Read(image)) {
    return false;
  }
  image->time_s += cameras_[c].clock_offset_s;  // on the rig's clock
  return true;
}

bool VideoFrameSource::Next(Frame* frame) {
  if (!learnt_) Learn();
  if (options_.max_frames > 0 && handed_out_ >= options_.max_frames) return false;
  Image first;
  if (!ReadImage(0, &first)) return false;
  const auto handed = std::chrono::steady_clock::now();
  const size_t n = sources_.size();
  const double tolerance = 0.5 / sources_[0]->fps();
  std::vector<Image> paired(n);
  // Live cameras each give their newest frame, so another camera's may be a frame ahead
  // of the first camera's: then the first camera's next (newest) frame is taken instead,
  // once or twice, before the frame is given up as unpaired.
  for (int attempt = 0;; ++attempt) {
    bool complete = true, ahead = false;
    for (size_t c = 1; c < n; ++c) {
      // Queue this camera's images up to the first one past the tolerance (a live
      // camera's: up to the first one not before it, as waiting for a later one would
      // cost a frame period), forget those before it, and take the nearest within it.
      std::deque<Image>& queue = queued_[c];
      const auto more = [&] {
        if (queue.empty()) return true;
        return live() ? queue.back().time_s < first.time_s - tolerance : queue.back().time_s <= first.time_s + tolerance;
      };
      while (!finished_[c] && more()) {
        Image image;
        if (!ReadImage(c, &image)) {
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
        complete = false;
        ahead = ahead || !queue.empty();
        continue;
      }
      paired[c] = queue[best];
      queue.erase(queue.begin(), queue.begin() + best + 1);
    }
    if (complete || !live() || !ahead || attempt == 2) break;
    for (size_t c = 1; c < n; ++c) {  // what was taken goes back for the next try
      if (!paired[c].bgr.empty()) queued_[c].push_front(std::move(paired[c]));
      paired[c] = Image();
    }
    if (!ReadImage(0, &first)) return false;
  }
  frame->index = first.index;
  frame->time_s = first.time_s;
  frame->latency_ms = first.latency_ms;
  frame->dropped = false;
  frame->images.assign(n, cv::Mat());
  frame->masks.assign(n, cv::Mat());
  frame->images[0] = first.bgr;
  for (size_t c = 1; c < n; ++c) {
    if (paired[c].bgr.empty()) {
      frame->dropped = true;
      continue;
    }
    frame->images[c] = paired[c].bgr;
    frame->latency_ms = std::max(frame->latency_ms, paired[c].latency_ms);
  }
  ++handed_out_;
  if (frame->dropped) {
    ++unpaired_;
    for (cv::Mat& image : frame->images) image = cv::Mat();
    return true;
  }
  for (size_t c = 0; c < n; ++c) {
    if (mask_sizes_.empty() || mask_sizes_[c].empty()) {
      frame->masks[c] = foreground_[c].Apply(frame->images[c]);
    } else {
      cv::Mat small;
      cv::resize(frame->images[c], small, mask_sizes_[c], 0, 0, cv::INTER_AREA);
      frame->masks[c] = foreground_[c].Apply(small);
    }
  }
  // Latency counts the foreground too: it is part of getting from capture to an estimate.
  frame->ready = std::chrono::steady_clock::now();
  frame->latency_ms += std::chrono::duration<double, std::milli>(frame->ready - handed).count();
  return true;
}

}  // namespace jgpm
