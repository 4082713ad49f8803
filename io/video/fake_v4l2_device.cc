#include "io/video/fake_v4l2_device.h"

#include <poll.h>
#include <sys/mman.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <ctime>
#include <thread>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

namespace jgpm {
namespace {

constexpr int kFd = 1000;                  // never a real descriptor of this process
constexpr int64_t kOffsetStep = 1 << 24;  // buffer k is mapped at offset k * step

int Failed(int error) {
  errno = error;
  return -1;
}

}  // namespace

std::vector<uint8_t> EncodeYuyv(const cv::Mat& bgr) {
  // OpenCV's 4:2:0 encoder uses the video-range BT.601 its YUYV decoder inverts; its
  // chroma, halved vertically too, is repeated on both rows.
  cv::Mat i420;
  cv::cvtColor(bgr, i420, cv::COLOR_BGR2YUV_I420);
  const int w = bgr.cols, h = bgr.rows;
  const uint8_t* y = i420.data;
  const uint8_t* u = y + static_cast<size_t>(w) * h;
  const uint8_t* v = u + static_cast<size_t>(w / 2) * (h / 2);
  std::vector<uint8_t> out(static_cast<size_t>(w) * h * 2);
  size_t i = 0;
  for (int r = 0; r < h; ++r) {
    for (int c = 0; c + 1 < w; c += 2) {
      const size_t chroma = static_cast<size_t>(r / 2) * (w / 2) + c / 2;
      out[i++] = y[static_cast<size_t>(r) * w + c];
      out[i++] = u[chroma];
      out[i++] = y[static_cast<size_t>(r) * w + c + 1];
      out[i++] = v[chroma];
    }
  }
  return out;
}

FakeV4l2Device::FakeV4l2Device(std::string path) : path_(std::move(path)) {}

int FakeV4l2Device::Stat(const std::string& path, struct stat* st) {
  if (path != path_) return Failed(ENOENT);
  *st = {};
  st->st_mode = S_IFCHR | 0660;
  return 0;
}

int FakeV4l2Device::Open(const std::string& path, int /*flags*/) {
  if (path != path_) return Failed(ENOENT);
  if (open_errno) return Failed(open_errno);
  return kFd;
}

int FakeV4l2Device::Close(int fd) { return fd == kFd ? 0 : Failed(EBADF); }

void FakeV4l2Device::Capture(const cv::Mat& bgr, uint32_t sequence, bool damaged) {
  cv::Mat sized = bgr;
  if (bgr.cols != width_ || bgr.rows != height_) cv::resize(bgr, sized, cv::Size(width_, height_));
  std::vector<uint8_t> bytes;
  if (pixel_format_ == V4L2_PIX_FMT_YUYV) {
    bytes = EncodeYuyv(sized);
  } else {
    cv::imencode(".jpg", sized, bytes, {cv::IMWRITE_JPEG_QUALITY, 90});
  }
  Fill(bytes, sequence, damaged);
}

void FakeV4l2Device::CaptureBytes(const std::vector<uint8_t>& bytes, uint32_t sequence) { Fill(bytes, sequence, false); }

void FakeV4l2Device::Fill(const std::vector<uint8_t>& bytes, uint32_t sequence, bool damaged) {
  ++captured_;
  if (!streaming_ || queued_.empty()) return;  // no free buffer: the frame is lost
  const uint32_t index = queued_.front();
  queued_.pop_front();
  std::vector<uint8_t>& buffer = buffers_[index];
  const size_t n = std::min(bytes.size(), buffer.size());
  std::copy(bytes.begin(), bytes.begin() + n, buffer.begin());
  timespec now;
  clock_gettime(CLOCK_MONOTONIC, &now);
  done_.push_back({index, sequence, static_cast<uint32_t>(n), {now.tv_sec, now.tv_nsec / 1000}, damaged});
  last_filled_ = sequence;
}

void FakeV4l2Device::Play(std::function<bool(cv::Mat*)> next, double fps) {
  next_ = std::move(next);
  play_fps_ = fps;
}

void FakeV4l2Device::Advance() {
  if (!next_ || unplugged_ || !streaming_) return;
  const auto now = std::chrono::steady_clock::now();
  const double elapsed = std::chrono::duration<double>(now - play_start_).count();
  while (!unplugged_ && play_sequence_ <= elapsed * play_fps_) {
    cv::Mat frame;
    if (!next_(&frame)) {
      unplugged_ = true;
      break;
    }
    Capture(frame, play_sequence_++);
  }
}

int FakeV4l2Device::Poll(int fd, int timeout_ms, short* revents) {
  if (fd != kFd) return Failed(EBADF);
  if (before_poll) before_poll(*this);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::milliseconds(timeout_ms);
  for (;;) {
    Advance();
    if (unplugged_) {
      *revents = POLLERR;
      return 1;
    }
    if (!done_.empty() || spurious_wakeups > 0) {
      spurious_wakeups -= done_.empty() ? 1 : 0;
      *revents = POLLIN;
      return 1;
    }
    const auto now = std::chrono::steady_clock::now();
    if (!next_ || !streaming_ || now >= deadline) {
      *revents = 0;
      return 0;
    }
    // Sleep until the next frame is due (or the deadline).
    const auto due = play_start_ + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                       std::chrono::duration<double>(play_sequence_ / play_fps_));
    std::this_thread::sleep_until(std::min(due, deadline));
  }
}

int FakeV4l2Device::Ioctl(int fd, unsigned long request, void* arg) {
  if (fd != kFd) return Failed(EBADF);
  if (unplugged_) return Failed(ENODEV);
  if (const auto it = fail.find(request); it != fail.end()) return Failed(it->second);
  switch (request) {
    case VIDIOC_QUERYCAP: {
      auto* cap = static_cast<v4l2_capability*>(arg);
      *cap = {};
      std::strncpy(reinterpret_cast<char*>(cap->driver), "jgpm-fake", sizeof(cap->driver) - 1);
      std::strncpy(reinterpret_cast<char*>(cap->card), "jgpm fake camera", sizeof(cap->card) - 1);
      std::strncpy(reinterpret_cast<char*>(cap->bus_info), "virtual", sizeof(cap->bus_info) - 1);
      cap->capabilities = capabilities | V4L2_CAP_DEVICE_CAPS;
      cap->device_caps = capabilities;
      return 0;
    }
    case VIDIOC_ENUM_FMT: {
      auto* d = static_cast<v4l2_fmtdesc*>(arg);
      if (d->index >= formats.size()) return Failed(EINVAL);
      d->pixelformat = formats[d->index];
      return 0;
    }
    case VIDIOC_ENUM_FRAMESIZES: {
      auto* s = static_cast<v4l2_frmsizeenum*>(arg);
      const int sizes[2][2] = {{forced_width ? forced_width : 640, forced_height ? forced_height : 480}, {320, 240}};
      if (s->index >= 2) return Failed(EINVAL);
      s->type = V4L2_FRMSIZE_TYPE_DISCRETE;
      s->discrete.width = sizes[s->index][0];
      s->discrete.height = sizes[s->index][1];
      return 0;
    }
    case VIDIOC_S_FMT: {
      auto* f = static_cast<v4l2_format*>(arg);
      if (std::find(formats.begin(), formats.end(), f->fmt.pix.pixelformat) == formats.end()) {
        f->fmt.pix.pixelformat = formats.empty() ? V4L2_PIX_FMT_YUYV : formats[0];
      }
      if (forced_width) f->fmt.pix.width = forced_width, f->fmt.pix.height = forced_height;
      pixel_format_ = f->fmt.pix.pixelformat;
      width_ = static_cast<int>(f->fmt.pix.width);
      height_ = static_cast<int>(f->fmt.pix.height);
      f->fmt.pix.bytesperline = pixel_format_ == V4L2_PIX_FMT_YUYV ? 2 * width_ : 0;
      f->fmt.pix.sizeimage = static_cast<uint32_t>(width_ * height_ * (pixel_format_ == V4L2_PIX_FMT_YUYV ? 2 : 3));
      return 0;
    }
    case VIDIOC_S_PARM: {
      auto* p = static_cast<v4l2_streamparm*>(arg);
      p->parm.capture.timeperframe.numerator = 1000;
      p->parm.capture.timeperframe.denominator = static_cast<uint32_t>(device_fps * 1000);
      return 0;
    }
    case VIDIOC_REQBUFS: {
      auto* r = static_cast<v4l2_requestbuffers*>(arg);
      if (r->memory != V4L2_MEMORY_MMAP) return Failed(EINVAL);
      r->count = granted_buffers ? static_cast<uint32_t>(granted_buffers) : r->count;
      buffers_.assign(r->count, std::vector<uint8_t>(static_cast<size_t>(width_) * height_ * 3));
      queued_.clear();
      done_.clear();
      return 0;
    }
    case VIDIOC_QUERYBUF: {
      auto* b = static_cast<v4l2_buffer*>(arg);
      if (b->index >= buffers_.size()) return Failed(EINVAL);
      b->length = static_cast<uint32_t>(buffers_[b->index].size());
      b->m.offset = static_cast<uint32_t>(b->index * kOffsetStep);
      return 0;
    }
    case VIDIOC_QBUF: {
      auto* b = static_cast<v4l2_buffer*>(arg);
      if (b->index >= buffers_.size() || std::count(queued_.begin(), queued_.end(), b->index)) return Failed(EINVAL);
      queued_.push_back(b->index);
      return 0;
    }
    case VIDIOC_DQBUF: {
      Advance();
      if (unplugged_) return Failed(ENODEV);
      if (done_.empty()) return Failed(EAGAIN);
      const Filled f = done_.front();
      done_.pop_front();
      auto* b = static_cast<v4l2_buffer*>(arg);
      b->index = f.index;
      b->bytesused = f.bytes;
      b->sequence = f.sequence;
      b->timestamp = f.timestamp;
      b->flags = V4L2_BUF_FLAG_TIMESTAMP_MONOTONIC | (f.damaged ? V4L2_BUF_FLAG_ERROR : 0);
      return 0;
    }
    case VIDIOC_STREAMON:
      streaming_ = true;
      play_start_ = std::chrono::steady_clock::now();  // a camera runs from here, read or not
      return 0;
    case VIDIOC_STREAMOFF:
      streaming_ = false;
      return 0;
    default:
      return Failed(ENOTTY);
  }
}

void* FakeV4l2Device::Mmap(size_t length, int fd, int64_t offset) {
  if (fd != kFd || offset % kOffsetStep != 0) return Failed(EINVAL), MAP_FAILED;
  const size_t index = static_cast<size_t>(offset / kOffsetStep);
  if (index >= buffers_.size() || length > buffers_[index].size()) return Failed(EINVAL), MAP_FAILED;
  return buffers_[index].data();
}

int FakeV4l2Device::Munmap(void* /*address*/, size_t /*length*/) { return 0; }

}  // namespace jgpm
