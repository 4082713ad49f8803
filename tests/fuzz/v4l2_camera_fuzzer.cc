// libFuzzer target: a camera driver answering anything. Every answer of the V4L2 calls
// (capabilities, formats, sizes, rates, buffer counts and lengths, dequeued buffers'
// index, size, sequence, flags and time, their bytes, poll's result, any errno) comes
// from the input. V4l2Camera must open, stream and read, or refuse with InputError, or
// end the stream; never crash, hang or hand out a frame that breaks its contract: the
// negotiated size, BGR, times and frame numbers that only go forward.
#include <fuzzer/FuzzedDataProvider.h>
#include <linux/videodev2.h>
#include <poll.h>
#include <sys/mman.h>

#include <cerrno>
#include <cstdint>
#include <cstring>
#include <memory>
#include <vector>

#include "io/base/error.h"
#include "io/video/v4l2_camera.h"

namespace {

class FuzzedDriver : public jgpm::V4l2Api {
 public:
  explicit FuzzedDriver(FuzzedDataProvider* in) : in_(*in) {}

  int Stat(const std::string&, struct stat* st) override {
    *st = {};
    st->st_mode = in_.ConsumeBool() ? S_IFCHR : S_IFREG;
    return 0;
  }
  int Open(const std::string&, int) override { return Fails() ? -1 : 7; }
  int Close(int) override { return 0; }
  int Ioctl(int, unsigned long request, void* arg) override {
    if (Fails()) return -1;
    switch (request) {
      case VIDIOC_QUERYCAP: {
        auto* cap = static_cast<v4l2_capability*>(arg);
        cap->capabilities = in_.ConsumeIntegral<uint32_t>();
        cap->device_caps = in_.ConsumeIntegral<uint32_t>();
        return 0;
      }
      case VIDIOC_ENUM_FMT: {
        auto* d = static_cast<v4l2_fmtdesc*>(arg);
        if (d->index > 4) return Error(EINVAL);
        const uint32_t known[] = {V4L2_PIX_FMT_YUYV, V4L2_PIX_FMT_MJPEG, V4L2_PIX_FMT_RGB24};
        d->pixelformat = in_.ConsumeBool() ? known[in_.ConsumeIntegralInRange(0, 2)] : in_.ConsumeIntegral<uint32_t>();
        return 0;
      }
      case VIDIOC_S_FMT: {
        auto* f = static_cast<v4l2_format*>(arg);
        if (in_.ConsumeBool()) f->fmt.pix.width = in_.ConsumeIntegralInRange<uint32_t>(0, 20000);
        if (in_.ConsumeBool()) f->fmt.pix.height = in_.ConsumeIntegralInRange<uint32_t>(0, 20000);
        if (!in_.ConsumeBool()) f->fmt.pix.pixelformat = in_.ConsumeIntegral<uint32_t>();
        f->fmt.pix.bytesperline = in_.ConsumeIntegralInRange<uint32_t>(0, 100000);
        width_ = f->fmt.pix.width;
        height_ = f->fmt.pix.height;
        return 0;
      }
      case VIDIOC_S_PARM: {
        auto* p = static_cast<v4l2_streamparm*>(arg);
        p->parm.capture.timeperframe.numerator = in_.ConsumeIntegral<uint32_t>();
        p->parm.capture.timeperframe.denominator = in_.ConsumeIntegral<uint32_t>();
        return 0;
      }
      case VIDIOC_REQBUFS: {
        auto* r = static_cast<v4l2_requestbuffers*>(arg);
        r->count = in_.ConsumeIntegralInRange<uint32_t>(0, 8);
        return 0;
      }
      case VIDIOC_QUERYBUF: {
        auto* b = static_cast<v4l2_buffer*>(arg);
        // Usually the size the format needs, sometimes anything.
        const size_t needed = static_cast<size_t>(width_) * height_ * 2;
        b->length = in_.ConsumeBool() && needed <= (8u << 20) ? static_cast<uint32_t>(needed)
                                                               : in_.ConsumeIntegralInRange<uint32_t>(0, 1 << 16);
        b->m.offset = b->index;
        return 0;
      }
      case VIDIOC_DQBUF: {
        auto* b = static_cast<v4l2_buffer*>(arg);
        b->index = in_.ConsumeBool() ? in_.ConsumeIntegralInRange<uint32_t>(0, 3) : in_.ConsumeIntegral<uint32_t>();
        b->bytesused = in_.ConsumeIntegral<uint32_t>();
        b->sequence = in_.ConsumeIntegral<uint32_t>();
        b->flags = in_.ConsumeIntegral<uint32_t>();
        b->timestamp.tv_sec = in_.ConsumeIntegralInRange<long>(-10, 1000000);
        b->timestamp.tv_usec = in_.ConsumeIntegralInRange<long>(0, 999999);
        if (b->index < buffers_.size()) {  // the frame's bytes
          std::vector<uint8_t>& buffer = buffers_[b->index];
          const std::vector<uint8_t> bytes = in_.ConsumeBytes<uint8_t>(in_.ConsumeIntegralInRange<size_t>(0, buffer.size()));
          std::copy(bytes.begin(), bytes.end(), buffer.begin());
        }
        return 0;
      }
      default:
        return 0;  // QBUF, STREAMON, STREAMOFF
    }
  }
  void* Mmap(size_t length, int, int64_t offset) override {
    if (Fails()) return MAP_FAILED;
    if (static_cast<size_t>(offset) != buffers_.size()) return Error(EINVAL), MAP_FAILED;
    buffers_.emplace_back(length);
    return buffers_.back().data();
  }
  int Munmap(void*, size_t) override { return 0; }
  int Poll(int, int, short* revents) override {
    if (Fails()) return -1;
    const int r = in_.ConsumeIntegralInRange(0, 1);
    *revents = r ? static_cast<short>(in_.ConsumeIntegral<uint16_t>() & (POLLIN | POLLERR | POLLHUP | POLLNVAL)) : 0;
    return r;
  }

 private:
  // With no input left every call fails as an unplugged device does, so that every loop
  // ends; before that, a call fails when the input says so, with one of the errnos a
  // driver gives.
  bool Fails() {
    if (in_.remaining_bytes() == 0) return Error(ENODEV), true;
    if (in_.ConsumeIntegralInRange(0, 7) != 0) return false;
    const int errors[] = {EINVAL, EBUSY, ENOSPC, ENODEV, EAGAIN, EIO, ENOTTY, EINTR, EACCES};
    Error(errors[in_.ConsumeIntegralInRange(0, 8)]);
    return true;
  }
  int Error(int e) {
    errno = e;
    return -1;
  }

  FuzzedDataProvider& in_;
  uint32_t width_ = 0, height_ = 0;
  std::vector<std::vector<uint8_t>> buffers_;  // mapped in order; each keeps its bytes where they are
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  FuzzedDataProvider in(data, size);
  auto driver = std::make_shared<FuzzedDriver>(&in);
  jgpm::V4l2Options options;
  options.timeout_ms = 1;
  options.format = in.PickValueInArray({"auto", "yuyv", "mjpg"});
  try {
    jgpm::V4l2Camera camera("/dev/video-fuzz", options, driver);
    jgpm::Image image;
    double last_time = -1e300;
    int last_index = -1;
    for (int k = 0; k < 8 && camera.Read(&image); ++k) {
      JGPM_CHECK(image.bgr.cols == camera.width() && image.bgr.rows == camera.height() && image.bgr.type() == CV_8UC3);
      JGPM_CHECK(image.time_s > last_time && image.index > last_index);
      last_time = image.time_s;
      last_index = image.index;
    }
  } catch (const jgpm::InputError&) {
  }
  return 0;
}
