// A live V4L2 camera as an image source, on the V4L2 API itself (io/video/v4l2_api.h): checked
// capabilities, a negotiated format (YUYV or MJPG, the size and rate asked for or the
// nearest the device gives), memory-mapped streaming buffers, poll with a timeout.
//
// Always the newest frame: a tracker slower than the camera must not fall behind it, so
// each Read takes every frame that is ready, keeps the newest and hands the older ones
// back to the driver. Frames lost that way, and those the driver dropped for want of a
// free buffer (gaps in the buffers' sequence numbers), are counted in skipped().
//
// A camera unplugged while streaming (ENODEV, POLLERR) ends the stream: Read returns
// false and end_reason() says so, so that everything tracked so far is still written. Times
// are the driver's capture timestamps, on one clock for every camera of the process so
// that several cameras pair by time.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "io/video/image_source.h"
#include "io/video/v4l2_api.h"

namespace jgpm {

struct V4l2Options {
  int width = 640, height = 480;  // asked for; the device may give another size
  double fps = 30;
  std::string format = "auto";    // auto (YUYV when offered, else MJPG), yuyv, mjpg
  int buffers = 4;
  int timeout_ms = 2000;          // no frame for this long is an error

  bool Check(std::string* why) const;
};

class V4l2Camera : public ImageSource {
 public:
  // InputError naming the device: missing, not a character device (a regular file, a
  // FIFO), not a capture device with streaming, no YUYV or MJPG, busy (EBUSY), fewer than
  // 2 buffers. The camera starts streaming at the first Read (so that nothing is dropped
  // while the tracker gets ready), which is where not enough USB bandwidth (ENOSPC) is
  // found.
  V4l2Camera(const std::string& path, const V4l2Options& options, std::shared_ptr<V4l2Api> api);
  ~V4l2Camera() override;
  V4l2Camera(const V4l2Camera&) = delete;
  V4l2Camera& operator=(const V4l2Camera&) = delete;

  const std::string& name() const override { return path_; }
  int width() const override { return width_; }
  int height() const override { return height_; }
  double fps() const override { return fps_; }
  int NumFrames() const override { return -1; }
  bool live() const override { return true; }
  // Starts streaming, when it has not started (the first Read does it). InputError for
  // not enough USB bandwidth (ENOSPC) or a busy device.
  void Start();
  bool Read(Image* image) override;
  int skipped() const override { return dropped_ + undecodable_; }
  std::string end_reason() const override { return ended_; }

  // What was asked and what the device gives, one line.
  const std::string& negotiation() const { return negotiation_; }
  int buffers() const { return static_cast<int>(buffers_.size()); }
  int dropped() const { return dropped_; }          // newer frames were ready, or gaps
  int undecodable() const { return undecodable_; }  // error-flagged or corrupt frames

 private:
  struct Buffer {
    void* start = nullptr;
    size_t length = 0;
  };
  int Xioctl(unsigned long request, void* arg);
  [[noreturn]] void Fail(const std::string& what, int error) const;
  void Requeue(uint32_t index);
  void Unplugged();
  void Release();  // stops streaming, unmaps, closes; never throws

  std::string path_;
  V4l2Options options_;
  std::shared_ptr<V4l2Api> api_;
  int fd_ = -1;
  bool streaming_ = false;
  uint32_t pixel_format_ = 0;
  int width_ = 0, height_ = 0, bytes_per_line_ = 0;
  double fps_ = 0;
  std::vector<Buffer> buffers_;
  std::string negotiation_;
  bool have_sequence_ = false;
  uint32_t first_sequence_ = 0, last_sequence_ = 0;
  int delivered_ = 0, dropped_ = 0, undecodable_ = 0;
  double last_captured_s_ = 0;
  long next_index_ = 0;
  std::string ended_;
};

// The camera a command line names: /dev/videoN through libv4l2, or fake:VIDEO, the
// software camera (io/video/fake_v4l2_device.h) playing a video file in real time at its frame
// rate and size. Errors as the constructor's, or the video's.
std::unique_ptr<V4l2Camera> OpenV4l2Camera(const std::string& device, const V4l2Options& options);

// One /dev/video* node as `jgpm devices` shows it.
struct V4l2DeviceInfo {
  std::string path, driver, card, bus;
  bool capture = false;              // a video capture node with streaming
  std::vector<std::string> formats;  // "YUYV 640x480 320x240 ...", one per pixel format
  std::string error;                 // why it could not be asked, when it could not
};
// Every /dev/video* (in number order) of `dir`; empty when there is none.
std::vector<V4l2DeviceInfo> ListV4l2Devices(V4l2Api& api, const std::string& dir = "/dev");

}  // namespace jgpm
