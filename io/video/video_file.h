// A recorded video as a camera's image source: anything OpenCV's FFmpeg back end decodes
// (AVI/MJPG, MP4/H.264, ...), with the timestamps the container gives.
//
// Damage is found before tracking starts, so that a bad file stops the run before anything
// is written: the constructor decodes the whole file once (at 320x240 MJPG about 0.2 ms a
// frame) to count the frames that decode. A frame that fails to decode part-way is skipped
// and counted (skipped()); a video that ends well before the frame count its container
// states (truncated), or has no frame at all, is refused.
#pragma once

#include <string>
#include <vector>

#include <opencv2/videoio.hpp>

#include "io/video/image_source.h"

namespace jgpm {

class VideoFileSource : public ImageSource {
 public:
  // InputError naming the file: missing, not a video OpenCV can open, no decodable frame,
  // truncated. The damage check decodes the whole file; with `sample` > 0 it also keeps
  // the frames Sample(sample) will ask for, so that learning the background costs no
  // second decoding (when every frame the container states decodes; else Sample decodes
  // again).
  explicit VideoFileSource(const std::string& path, int sample = 0);

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
};

}  // namespace jgpm
