// Where one camera's colour images come from: a video file (io/video/video_file.h), a folder of
// images (io/video/image_folder.h) or a live V4L2 camera (io/video/v4l2_camera.h). The tracker turns
// them into foreground masks (tracker/frames/foreground.h) and pairs several cameras' images by
// time (tracker/frames/video_frame_source.h).
#pragma once

#include <string>
#include <vector>

#include <opencv2/core/mat.hpp>

namespace jgpm {

struct Image {
  cv::Mat bgr;            // CV_8UC3
  double time_s = 0;      // since the source's first image (the capture time, when live)
  int index = 0;          // frame number in the source, from 0 (live: counts drops too)
  double latency_ms = 0;  // live only: from capture to when Read returned it
};

class ImageSource {
 public:
  virtual ~ImageSource() = default;
  // The file, folder or device, for messages.
  virtual const std::string& name() const = 0;
  virtual int width() const = 0;
  virtual int height() const = 0;
  virtual double fps() const = 0;
  // Images in the source; -1 when unknown (live).
  virtual int NumFrames() const = 0;
  virtual bool live() const { return false; }
  // The next image; false at the end (or, live, when the device went away: see end_reason()).
  // InputError naming the file or device for anything that cannot go on.
  virtual bool Read(Image* image) = 0;
  // Frames that were lost on the way: failed to decode (files) or dropped because
  // processing was slower than capture (live).
  virtual int skipped() const { return 0; }
  // Why a live source stopped early ("" when it did not).
  virtual std::string end_reason() const { return ""; }
  // Up to `n` images spread evenly over the whole source, read apart from Read's position
  // (to learn the background from); empty for live sources.
  virtual std::vector<cv::Mat> Sample(int /*n*/) { return {}; }
};

// Indices of up to n of `count` items spread evenly over them (all when n >= count).
inline std::vector<int> EvenSample(int count, int n) {
  std::vector<int> picked;
  if (count <= 0 || n <= 0) return picked;
  if (n >= count) n = count;
  for (int i = 0; i < n; ++i) picked.push_back(static_cast<int>((2 * i + 1) * static_cast<long long>(count) / (2 * n)));
  return picked;
}

}  // namespace jgpm
