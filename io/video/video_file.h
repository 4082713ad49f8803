// A recorded video as a camera's image source: anything OpenCV's FFmpeg back end decodes
// (AVI/MJPG, MP4/H.264, ...), with the timestamps the container gives.
//
// Damage is found before tracking starts, so that a bad file stops the run before anything
// is written: the constructor decodes the whole file once (at 320x240 MJPG about 0.2 ms a
// frame) to count the frames that decode; or, when there is no first pass to share it
// with (the background is given), as the frames are read (VideoCheck). A frame that fails to decode part-way is skipped
// and counted (skipped()); a video that ends well before the frame count its container
// states (truncated), or has no frame at all, is refused.
#pragma once

#include <string>
#include <vector>

#include <opencv2/videoio.hpp>

#include "io/video/image_source.h"

namespace jgpm {

// When damage is looked for: in a first pass over the whole file (before anything is
// tracked), or as the frames are read (one decoding in all: Read throws at the end of a
// truncated file and on a frame of another size; the caller's outputs, written to a
// `.partial` folder, go with the run).
enum class VideoCheck { kFirst, kAsItGoes };

class VideoFileSource : public ImageSource {
 public:
  // InputError naming the file: missing, not a video OpenCV can open, no decodable frame,
  // truncated. The damage check decodes the whole file; with `sample` > 0 it also keeps
  // the frames Sample(sample) will ask for, so that learning the background costs no
  // second decoding (when every frame the container states decodes; else Sample decodes
  // again). kAsItGoes: only the first frame is decoded here, and NumFrames is the
  // container's count (-1 when it states none).
  explicit VideoFileSource(const std::string& path, int sample = 0, VideoCheck check = VideoCheck::kFirst);

  const std::string& name() const override { return path_; }
  int width() const override { return width_; }
  int height() const override { return height_; }
  double fps() const override { return fps_; }
  int NumFrames() const override { return decodable_; }
  bool Read(Image* image) override;
  int skipped() const override { return skipped_; }
  std::vector<cv::Mat> Sample(int n) override;

 private:
  std::string path_;
  cv::VideoCapture video_;
  int width_ = 0, height_ = 0;
  double fps_ = 0;
  int stated_ = 0;     // the container's frame count
  int decodable_ = 0;  // frames that decode
  int next_ = 0;       // position in the container, decodable or not
  int skipped_ = 0;
  int sampled_for_ = 0;           // the n whose Sample was kept during the check
  std::vector<cv::Mat> sampled_;
  bool as_it_goes_ = false;
  cv::Mat first_;  // kAsItGoes: the first frame, decoded by the constructor
  double first_time_s_ = 0;

  void CheckSize(const cv::Mat& frame, int index) const;
  void CheckComplete(int frames) const;
};

}  // namespace jgpm
