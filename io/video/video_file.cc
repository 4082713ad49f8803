#include "io/video/video_file.h"

#include <cmath>
#include <cstdlib>
#include <filesystem>

#include "io/base/error.h"

namespace jgpm {
namespace {

// A damaged frame is ours to report, once, with the file named: FFmpeg's own messages
// ("[mjpeg @ 0x...] No JPEG data found") are turned off unless the user asks for them.
// OpenCV reads the level when its FFmpeg back end starts, i.e. at the first capture.
void QuietFfmpeg() {
  static const bool quiet = [] { return setenv("OPENCV_FFMPEG_LOGLEVEL", "0", 0) == 0; }();
  (void)quiet;
}

// The next frame that decodes, past up to a few that do not (OpenCV's read fails on one
// and would end the video there); false at the end.
bool ReadDecodable(cv::VideoCapture* video, int stated, cv::Mat* frame) {
  constexpr int kBadInARow = 16;
  for (int tries = 0; tries <= kBadInARow; ++tries) {
    if (video->read(*frame)) return true;
    if (stated <= 0 || video->get(cv::CAP_PROP_POS_FRAMES) >= stated) return false;
  }
  return false;
}

cv::VideoCapture OpenVideo(const std::string& path) {
  QuietFfmpeg();
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) ThrowInputError(path, "no such video file");
  cv::VideoCapture video(path, cv::CAP_FFMPEG);
  if (!video.isOpened()) ThrowInputError(path, "not a video OpenCV can open (expected e.g. AVI/MJPG or MP4/H.264)");
  return video;
}

}  // namespace

VideoFileSource::VideoFileSource(const std::string& path, int sample, VideoCheck check)
    : path_(path), video_(OpenVideo(path)), as_it_goes_(check == VideoCheck::kAsItGoes) {
  width_ = static_cast<int>(video_.get(cv::CAP_PROP_FRAME_WIDTH));
  height_ = static_cast<int>(video_.get(cv::CAP_PROP_FRAME_HEIGHT));
  fps_ = video_.get(cv::CAP_PROP_FPS);
  if (!(fps_ > 0 && fps_ <= 1000)) ThrowInputError(path, "states no usable frame rate (" + std::to_string(fps_) + ")");
  const double stated = video_.get(cv::CAP_PROP_FRAME_COUNT);
  stated_ = std::isfinite(stated) && stated > 0 ? static_cast<int>(stated) : 0;
  if (as_it_goes_) {
    // No first pass: the first frame is decoded now (a video with none is refused before
    // anything is made), the rest are checked as they are read.
    if (!ReadDecodable(&video_, stated_, &first_)) ThrowInputError(path, "has no frame that decodes (empty or damaged video)");
    first_time_s_ = video_.get(cv::CAP_PROP_POS_MSEC) / 1000;
    CheckSize(first_, 0);
    decodable_ = stated_ > 0 ? stated_ : -1;
    return;
  }
  // The damage check: decode everything once. OpenCV skips a frame that does not decode
  // and goes on; the container time then jumps, which is how skipped frames are counted.
  cv::VideoCapture scan = OpenVideo(path);
  cv::Mat frame;
  double last_ms = -1;
  int gaps = 0;
  // Sample's frames, by their decodable index, if every stated frame decodes.
  const std::vector<int> wanted = EvenSample(stated_, sample);
  size_t w = 0;
  while (ReadDecodable(&scan, stated_, &frame)) {
    if (w < wanted.size() && decodable_ == wanted[w]) {
      sampled_.push_back(frame.clone());
      ++w;
    }
    CheckSize(frame, decodable_);
    const double ms = scan.get(cv::CAP_PROP_POS_MSEC);
    if (last_ms >= 0) gaps += std::max(0, static_cast<int>(std::lround((ms - last_ms) * fps_ / 1000)) - 1);
    last_ms = ms;
    ++decodable_;
  }
  if (decodable_ == 0) ThrowInputError(path, "has no frame that decodes (empty or damaged video)");
  if (decodable_ == stated_ && w == wanted.size()) {
    sampled_for_ = sample;
  } else {
    sampled_.clear();
  }
  CheckComplete(decodable_ + gaps);
}

void VideoFileSource::CheckSize(const cv::Mat& frame, int index) const {
  if (frame.cols != width_ || frame.rows != height_) {
    ThrowInputError(path_, "frame " + std::to_string(index) + " is " + std::to_string(frame.cols) + "x" +
                               std::to_string(frame.rows) + ", not the stated " + std::to_string(width_) + "x" +
                               std::to_string(height_));
  }
}

void VideoFileSource::CheckComplete(int frames) const {
  // A cut file keeps its header's count; a few frames of slack for containers that round.
  if (stated_ > 0 && frames < stated_ - std::max(2, stated_ / 100)) {
    ThrowInputError(path_, "is truncated: only " + std::to_string(frames) + " of the " + std::to_string(stated_) +
                               " frames its container states are there");
  }
}

bool VideoFileSource::Read(Image* image) {
  cv::Mat frame;
  double t = 0;
  if (!first_.empty()) {
    frame = std::move(first_);
    first_ = cv::Mat();
    t = first_time_s_;
  } else {
    if (!ReadDecodable(&video_, stated_, &frame)) {
      if (as_it_goes_) CheckComplete(next_);  // next_: the frames read and skipped
      return false;
    }
    t = video_.get(cv::CAP_PROP_POS_MSEC) / 1000;
    if (as_it_goes_) CheckSize(frame, next_);
  }
  const int index = static_cast<int>(std::lround(t * fps_));
  skipped_ += std::max(0, index - next_);  // frames that did not decode
  next_ = index + 1;
  image->bgr = frame;
  image->time_s = t;
  image->index = index;
  image->latency_ms = 0;
  return true;
}

std::vector<cv::Mat> VideoFileSource::Sample(int n) {
  if (n > 0 && n == sampled_for_) {
    sampled_for_ = 0;
    return std::move(sampled_);  // EvenSample(decodable_, n): decodable_ is stated_
  }
  const std::vector<int> wanted = EvenSample(decodable_, n);
  std::vector<cv::Mat> frames;
  cv::VideoCapture scan = OpenVideo(path_);
  cv::Mat frame;
  size_t w = 0;
  for (int k = 0; w < wanted.size() && ReadDecodable(&scan, stated_, &frame); ++k) {  // k counts decodable ones
    if (k != wanted[w]) continue;
    frames.push_back(frame.clone());
    ++w;
  }
  return frames;
}

}  // namespace jgpm
