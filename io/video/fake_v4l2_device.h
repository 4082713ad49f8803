// A V4L2 camera in software that speaks io/video/v4l2_api.h, for two uses:
//  - tests: every answer can be scripted (capabilities, formats, the size it forces, the
//    buffers it grants, an errno per ioctl, frames with chosen sequence numbers, frames
//    flagged as damaged, spurious wake-ups, unplugging);
//  - the whole live path without a camera (`jgpm track --device fake:VIDEO`): frames
//    from a callback delivered at a frame rate by the wall clock.
// It behaves as a driver does where it matters: a frame is captured into the oldest
// queued buffer and waits there until dequeued; with no buffer queued the frame is lost,
// and only its sequence number shows it.
#pragma once

#include <linux/videodev2.h>

#include <chrono>
#include <deque>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include <opencv2/core/mat.hpp>

#include "io/video/v4l2_api.h"

namespace jgpm {

class FakeV4l2Device : public V4l2Api {
 public:
  explicit FakeV4l2Device(std::string path = "/dev/video-fake");

  // The script (set before the capture opens the device).
  uint32_t capabilities = V4L2_CAP_VIDEO_CAPTURE | V4L2_CAP_STREAMING;
  std::vector<uint32_t> formats = {V4L2_PIX_FMT_YUYV, V4L2_PIX_FMT_MJPEG};
  int forced_width = 0, forced_height = 0;  // the size S_FMT gives (0: the one asked)
  double device_fps = 30;                   // the rate S_PARM gives
  int granted_buffers = 0;                  // REQBUFS grants this many (0: as asked)
  int open_errno = 0;                       // Open fails with it (e.g. EBUSY)
  std::map<unsigned long, int> fail;        // an ioctl request -> the errno it fails with
  int spurious_wakeups = 0;                 // Polls that say "ready" with nothing ready
  std::function<void(FakeV4l2Device&)> before_poll;  // runs at the start of every Poll

  // Scripted frames: captured now, as the device's frame `sequence` (`damaged`: flagged
  // V4L2_BUF_FLAG_ERROR, as a driver marks a frame lost in transfer).
  void Capture(const cv::Mat& bgr, uint32_t sequence, bool damaged = false);
  // A frame whose bytes are these, whatever the format (a corrupt MJPG, a short frame).
  void CaptureBytes(const std::vector<uint8_t>& bytes, uint32_t sequence);
  // Real time: frame k of `next` is captured k / fps seconds after streaming starts, read
  // or not; when `next` has no more, the device is unplugged.
  void Play(std::function<bool(cv::Mat*)> next, double fps);
  // From now on every call fails with ENODEV and poll says POLLERR.
  void Unplug() { unplugged_ = true; }

  int width() const { return width_; }
  int height() const { return height_; }
  uint32_t pixel_format() const { return pixel_format_; }
  int captured() const { return captured_; }  // frames the camera saw, lost ones included
  // The sequence number of the last frame put into a buffer (-1: none yet).
  long last_filled() const { return last_filled_; }
  bool streaming() const { return streaming_; }

  int Stat(const std::string& path, struct stat* st) override;
  int Open(const std::string& path, int flags) override;
  int Close(int fd) override;
  int Ioctl(int fd, unsigned long request, void* arg) override;
  void* Mmap(size_t length, int fd, int64_t offset) override;
  int Munmap(void* address, size_t length) override;
  int Poll(int fd, int timeout_ms, short* revents) override;

 private:
  struct Filled {
    uint32_t index, sequence, bytes;
    timeval timestamp;
    bool damaged;
  };
  void Advance();  // real time: capture what is due
  void Fill(const std::vector<uint8_t>& bytes, uint32_t sequence, bool damaged);

  std::string path_;
  uint32_t pixel_format_ = V4L2_PIX_FMT_YUYV;
  int width_ = 640, height_ = 480;
  std::vector<std::vector<uint8_t>> buffers_;
  std::deque<uint32_t> queued_;  // buffers free for capture, oldest first
  std::deque<Filled> done_;      // captured, waiting to be dequeued
  bool streaming_ = false, unplugged_ = false;
  int captured_ = 0;
  long last_filled_ = -1;
  std::function<bool(cv::Mat*)> next_;
  double play_fps_ = 0;
  std::chrono::steady_clock::time_point play_start_;
  uint32_t play_sequence_ = 0;
};

// A BGR image (even width and height) as a camera's YUYV, the BT.601 video range that
// OpenCV's COLOR_YUV2BGR_YUYV converts back.
std::vector<uint8_t> EncodeYuyv(const cv::Mat& bgr);

}  // namespace jgpm
