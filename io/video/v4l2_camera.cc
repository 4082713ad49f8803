#include "io/video/v4l2_camera.h"

#include <fcntl.h>
#include <linux/videodev2.h>
#include <poll.h>
#include <sys/mman.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <mutex>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "io/base/error.h"
#include "io/video/fake_v4l2_device.h"
#include "io/video/video_file.h"

namespace jgpm {
namespace {

std::string FourCc(uint32_t f) {
  std::string s;
  for (int i = 0; i < 4; ++i) s += static_cast<char>((f >> (8 * i)) & 0xFF);
  while (!s.empty() && s.back() == ' ') s.pop_back();
  return s;
}

double MonotonicNow() {
  timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return t.tv_sec + t.tv_nsec * 1e-9;
}

// One time origin for every camera of the process, so that their frames pair by time.
double Since(double capture_s) {
  static std::once_flag once;
  static double origin = 0;
  std::call_once(once, [capture_s] { origin = capture_s; });
  return capture_s - origin;
}

std::string Busy(const std::string& path) {
  return "is busy: another program is using it (close it; `fuser -v " + path + "` shows which)";
}

}  // namespace

bool V4l2Options::Check(std::string* why) const {
  auto fail = [why](const std::string& what) { return *why = what, false; };
  if (width < 16 || height < 16 || width > 16384 || height > 16384) return fail("the image size asked must be 16-16384 pixels a side");
  if (!(fps >= 1 && fps <= 1000)) return fail("the frame rate asked must be 1-1000 frames/s");
  if (format != "auto" && format != "yuyv" && format != "mjpg") return fail("the pixel format must be auto, yuyv or mjpg");
  if (buffers < 2 || buffers > 32) return fail("2-32 streaming buffers");
  if (timeout_ms < 1) return fail("the frame timeout must be at least 1 ms");
  return true;
}

[[noreturn]] void V4l2Camera::Fail(const std::string& what, int error) const {
  if (error == EBUSY) ThrowInputError(path_, Busy(path_));
  ThrowInputError(path_, what + " (" + std::strerror(error) + ")");
}

int V4l2Camera::Xioctl(unsigned long request, void* arg) { return api_->Ioctl(fd_, request, arg); }

V4l2Camera::V4l2Camera(const std::string& path, const V4l2Options& options, std::shared_ptr<V4l2Api> api)
    : path_(path), options_(options), api_(std::move(api)) {
  std::string why;
  if (!options.Check(&why)) ThrowInputError(path, why);
  struct stat st {};
  if (api_->Stat(path, &st) != 0) ThrowInputError(path, "no such device (jgpm devices lists the cameras)");
  if (!S_ISCHR(st.st_mode)) {
    const char* what = S_ISREG(st.st_mode) ? "a regular file" : S_ISFIFO(st.st_mode) ? "a FIFO" : S_ISDIR(st.st_mode) ? "a folder" : "not a device";
    ThrowInputError(path, std::string("is ") + what + ", not a video device (jgpm devices lists the cameras)");
  }
  fd_ = api_->Open(path, O_RDWR | O_NONBLOCK);
  if (fd_ < 0) {
    const int e = errno;
    if (e == EACCES) ThrowInputError(path, "permission denied (add yourself to the `video` group, then log in again)");
    Fail("cannot be opened", e);
  }
  try {
    v4l2_capability cap{};
    if (Xioctl(VIDIOC_QUERYCAP, &cap) < 0) Fail("is not a V4L2 device (VIDIOC_QUERYCAP failed)", errno);
    const uint32_t caps = (cap.capabilities & V4L2_CAP_DEVICE_CAPS) ? cap.device_caps : cap.capabilities;
    if (!(caps & V4L2_CAP_VIDEO_CAPTURE)) {
      ThrowInputError(path, "is not a video capture device (a camera often has a second, metadata node: try the "
                            "other /dev/videoN of `jgpm devices`)");
    }
    if (!(caps & V4L2_CAP_STREAMING)) ThrowInputError(path, "cannot stream (no V4L2_CAP_STREAMING)");

    // The format: YUYV or MJPG, whichever is asked for and offered.
    std::vector<uint32_t> offered;
    for (uint32_t i = 0;; ++i) {
      v4l2_fmtdesc d{};
      d.index = i;
      d.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
      if (Xioctl(VIDIOC_ENUM_FMT, &d) < 0) break;
      offered.push_back(d.pixelformat);
    }
    const auto has = [&offered](uint32_t f) { return std::find(offered.begin(), offered.end(), f) != offered.end(); };
    uint32_t wanted = 0;
    if (options.format == "yuyv" || (options.format == "auto" && has(V4L2_PIX_FMT_YUYV))) {
      wanted = V4L2_PIX_FMT_YUYV;
    } else if (options.format == "mjpg" || options.format == "auto") {
      wanted = V4L2_PIX_FMT_MJPEG;
    } else {
      ThrowInputError("--pixel-format " + options.format, "expected auto, yuyv or mjpg");
    }
    if (!has(wanted)) {
      std::string list;
      for (uint32_t f : offered) list += (list.empty() ? "" : ", ") + FourCc(f);
      ThrowInputError(path, "does not offer " + FourCc(wanted) + " (it offers " + (list.empty() ? "nothing" : list) +
                                "; jgpm reads YUYV and MJPG)");
    }
    v4l2_format fmt{};
    fmt.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
    fmt.fmt.pix.width = options.width;
    fmt.fmt.pix.height = options.height;
    fmt.fmt.pix.pixelformat = wanted;
    fmt.fmt.pix.field = V4L2_FIELD_ANY;
    if (Xioctl(VIDIOC_S_FMT, &fmt) < 0) Fail("refused the format " + FourCc(wanted), errno);
    if (fmt.fmt.pix.pixelformat != wanted) {
      ThrowInputError(path, "gave " + FourCc(fmt.fmt.pix.pixelformat) + " when asked for " + FourCc(wanted));
    }
    pixel_format_ = wanted;
    width_ = static_cast<int>(fmt.fmt.pix.width);
    height_ = static_cast<int>(fmt.fmt.pix.height);
    bytes_per_line_ = static_cast<int>(fmt.fmt.pix.bytesperline);
    if (width_ < 16 || height_ < 16 || width_ > 16384 || height_ > 16384) {
      ThrowInputError(path, "gave an image of " + std::to_string(fmt.fmt.pix.width) + "x" +
                                std::to_string(fmt.fmt.pix.height) + " pixels");
    }
    if (wanted == V4L2_PIX_FMT_YUYV && bytes_per_line_ < 2 * width_) bytes_per_line_ = 2 * width_;

    // The frame rate: asked for; what the device says it gives (some cannot be asked).
    fps_ = options.fps;
    v4l2_streamparm parm{};
    parm.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
    parm.parm.capture.timeperframe.numerator = 1000;
    parm.parm.capture.timeperframe.denominator = static_cast<uint32_t>(std::lround(options.fps * 1000));
    if (Xioctl(VIDIOC_S_PARM, &parm) == 0 && parm.parm.capture.timeperframe.numerator > 0 &&
        parm.parm.capture.timeperframe.denominator > 0) {
      const double given = static_cast<double>(parm.parm.capture.timeperframe.denominator) /
                           parm.parm.capture.timeperframe.numerator;
      if (given >= 1 && given <= 1000) fps_ = given;  // else the driver's answer is nonsense
    }
    char line[256];
    std::snprintf(line, sizeof(line), "asked %dx%d %s at %g fps, %s gives %dx%d %s at %g fps", options.width,
                  options.height, FourCc(wanted).c_str(), options.fps, path.c_str(), width_, height_,
                  FourCc(wanted).c_str(), fps_);
    negotiation_ = line;

    // Buffers, mapped and queued.
    v4l2_requestbuffers req{};
    req.count = static_cast<uint32_t>(std::max(2, options.buffers));
    req.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
    req.memory = V4L2_MEMORY_MMAP;
    if (Xioctl(VIDIOC_REQBUFS, &req) < 0) {
      if (errno == EINVAL) ThrowInputError(path, "does not support memory-mapped streaming");
      Fail("refused streaming buffers", errno);
    }
    if (req.count < 2) {
      ThrowInputError(path, "granted " + std::to_string(req.count) + " streaming buffer(s); at least 2 are needed");
    }
    for (uint32_t i = 0; i < req.count; ++i) {
      v4l2_buffer b{};
      b.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
      b.memory = V4L2_MEMORY_MMAP;
      b.index = i;
      if (Xioctl(VIDIOC_QUERYBUF, &b) < 0) Fail("cannot describe buffer " + std::to_string(i), errno);
      void* start = api_->Mmap(b.length, fd_, b.m.offset);
      if (start == MAP_FAILED) Fail("cannot map buffer " + std::to_string(i), errno);
      buffers_.push_back({start, b.length});
      if (Xioctl(VIDIOC_QBUF, &b) < 0) Fail("cannot queue buffer " + std::to_string(i), errno);
    }
  } catch (...) {
    Release();  // a constructor that throws runs no destructor
    throw;
  }
}

V4l2Camera::~V4l2Camera() { Release(); }

void V4l2Camera::Release() {
  if (fd_ < 0) return;
  if (streaming_) {
    v4l2_buf_type type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
    Xioctl(VIDIOC_STREAMOFF, &type);
    streaming_ = false;
  }
  for (const Buffer& b : buffers_) api_->Munmap(b.start, b.length);
  buffers_.clear();
  api_->Close(fd_);
  fd_ = -1;
}

void V4l2Camera::Start() {
  if (streaming_ || !ended_.empty()) return;
  v4l2_buf_type type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
  if (Xioctl(VIDIOC_STREAMON, &type) < 0) {
    if (errno == ENOSPC) {
      ThrowInputError(path_, "not enough USB bandwidth for " + std::to_string(width_) + "x" + std::to_string(height_) +
                                 " " + FourCc(pixel_format_) +
                                 " (ask a smaller --size, a lower --device-fps or --pixel-format mjpg, or plug the "
                                 "camera into another USB port or hub)");
    }
    Fail("refused to start streaming", errno);
  }
  streaming_ = true;
}

void V4l2Camera::Requeue(uint32_t index) {
  v4l2_buffer b{};
  b.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
  b.memory = V4L2_MEMORY_MMAP;
  b.index = index;
  if (Xioctl(VIDIOC_QBUF, &b) < 0 && errno != ENODEV) Fail("cannot queue buffer " + std::to_string(index), errno);
}

void V4l2Camera::Unplugged() {
  ended_ = path_ + " went away (unplugged?) after " + std::to_string(delivered_) + " frames";
}

bool V4l2Camera::Read(Image* image) {
  Start();
  while (ended_.empty()) {
    short revents = 0;
    const int r = api_->Poll(fd_, options_.timeout_ms, &revents);
    if (r < 0) {
      if (errno == EINTR) continue;
      if (errno == ENODEV) break;
      Fail("poll failed", errno);
    }
    if (r == 0) {
      ThrowInputError(path_, "no frame within " + std::to_string(options_.timeout_ms) +
                                 " ms (is the camera streaming? a very long exposure?)");
    }
    if (revents & (POLLERR | POLLHUP | POLLNVAL)) break;
    // Everything ready, oldest first: keep the newest, give the rest back.
    bool have = false;
    v4l2_buffer newest{};
    for (;;) {
      v4l2_buffer b{};
      b.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
      b.memory = V4L2_MEMORY_MMAP;
      if (Xioctl(VIDIOC_DQBUF, &b) < 0) {
        if (errno == EAGAIN) break;
        if (errno == ENODEV) {
          if (have) Requeue(newest.index);
          Unplugged();
          return false;
        }
        if (errno == EIO) {  // a frame lost in transfer; its buffer is still ours to queue
          ++undecodable_;
          continue;
        }
        Fail("cannot take a frame (VIDIOC_DQBUF)", errno);
      }
      if (b.index >= buffers_.size()) ThrowInputError(path_, "returned buffer " + std::to_string(b.index) + " it never had");
      if (have_sequence_ && b.sequence > last_sequence_ + 1) {
        dropped_ += static_cast<int>(std::min<uint32_t>(b.sequence - last_sequence_ - 1, 1000000));
      }
      if (!have_sequence_) first_sequence_ = b.sequence;
      have_sequence_ = true;
      last_sequence_ = b.sequence;
      if (have) {
        Requeue(newest.index);
        ++dropped_;
      }
      newest = b;
      have = true;
      if (b.flags & V4L2_BUF_FLAG_ERROR) {
        Requeue(b.index);
        ++undecodable_;
        have = false;
      }
    }
    if (!have) continue;
    const Buffer& buffer = buffers_[newest.index];
    const size_t used = std::min<size_t>(newest.bytesused ? newest.bytesused : buffer.length, buffer.length);
    cv::Mat bgr;
    if (pixel_format_ == V4L2_PIX_FMT_YUYV) {
      if (used >= static_cast<size_t>(bytes_per_line_) * height_) {
        const cv::Mat yuyv(height_, width_, CV_8UC2, buffer.start, bytes_per_line_);
        cv::cvtColor(yuyv, bgr, cv::COLOR_YUV2BGR_YUYV);
      }
    } else {
      bgr = cv::imdecode(cv::Mat(1, static_cast<int>(used), CV_8UC1, buffer.start), cv::IMREAD_COLOR);
    }
    Requeue(newest.index);
    if (bgr.cols != width_ || bgr.rows != height_) {  // short or corrupt
      ++undecodable_;
      continue;
    }
    // Times and frame numbers only go forward, whatever the driver says (a camera that
    // restarts its sequence, or stamps no time).
    double captured = newest.timestamp.tv_sec + newest.timestamp.tv_usec * 1e-6;
    if (delivered_ > 0 && !(captured > last_captured_s_)) captured = last_captured_s_ + 1 / fps_;
    last_captured_s_ = captured;
    const long index = static_cast<long>(newest.sequence) - static_cast<long>(first_sequence_);
    next_index_ = std::max<long>(next_index_, std::min<long>(index, next_index_ + 1000000));
    image->bgr = bgr;
    image->time_s = Since(captured);
    image->index = static_cast<int>(next_index_++);
    const bool monotonic = (newest.flags & V4L2_BUF_FLAG_TIMESTAMP_MASK) == V4L2_BUF_FLAG_TIMESTAMP_MONOTONIC;
    image->latency_ms = monotonic ? std::max(0.0, 1000 * (MonotonicNow() - captured)) : 0.0;
    ++delivered_;
    return true;
  }
  if (ended_.empty()) Unplugged();
  return false;
}

std::unique_ptr<V4l2Camera> OpenV4l2Camera(const std::string& device, const V4l2Options& options) {
  if (device.rfind("fake:", 0) != 0) return std::make_unique<V4l2Camera>(device, options, std::make_shared<LibV4l2Api>());
  auto video = std::make_shared<VideoFileSource>(device.substr(5));
  auto fake = std::make_shared<FakeV4l2Device>(device);
  fake->forced_width = video->width();
  fake->forced_height = video->height();
  fake->device_fps = video->fps();
  fake->Play(
      [video](cv::Mat* frame) {
        Image image;
        if (!video->Read(&image)) return false;
        *frame = image.bgr;
        return true;
      },
      video->fps());
  return std::make_unique<V4l2Camera>(device, options, fake);
}

std::vector<V4l2DeviceInfo> ListV4l2Devices(V4l2Api& api, const std::string& dir) {
  std::vector<std::pair<long, std::string>> nodes;
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(dir, ec)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind("video", 0) != 0) continue;
    char* end = nullptr;
    const long number = std::strtol(name.c_str() + 5, &end, 10);
    if (end == name.c_str() + 5 || *end != '\0') continue;
    nodes.emplace_back(number, entry.path().string());
  }
  std::sort(nodes.begin(), nodes.end());
  std::vector<V4l2DeviceInfo> devices;
  for (const auto& [number, path] : nodes) {
    V4l2DeviceInfo info;
    info.path = path;
    const int fd = api.Open(path, O_RDWR | O_NONBLOCK);
    if (fd < 0) {
      info.error = errno == EBUSY ? "busy" : std::strerror(errno);
      devices.push_back(info);
      continue;
    }
    v4l2_capability cap{};
    if (api.Ioctl(fd, VIDIOC_QUERYCAP, &cap) < 0) {
      info.error = std::string("not a V4L2 device (") + std::strerror(errno) + ")";
    } else {
      info.driver = reinterpret_cast<const char*>(cap.driver);
      info.card = reinterpret_cast<const char*>(cap.card);
      info.bus = reinterpret_cast<const char*>(cap.bus_info);
      const uint32_t caps = (cap.capabilities & V4L2_CAP_DEVICE_CAPS) ? cap.device_caps : cap.capabilities;
      info.capture = (caps & V4L2_CAP_VIDEO_CAPTURE) && (caps & V4L2_CAP_STREAMING);
      for (uint32_t i = 0; info.capture; ++i) {
        v4l2_fmtdesc d{};
        d.index = i;
        d.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
        if (api.Ioctl(fd, VIDIOC_ENUM_FMT, &d) < 0) break;
        std::string line = FourCc(d.pixelformat);
        for (uint32_t k = 0; k < 64; ++k) {
          v4l2_frmsizeenum s{};
          s.index = k;
          s.pixel_format = d.pixelformat;
          if (api.Ioctl(fd, VIDIOC_ENUM_FRAMESIZES, &s) < 0) break;
          if (s.type == V4L2_FRMSIZE_TYPE_DISCRETE) {
            line += " " + std::to_string(s.discrete.width) + "x" + std::to_string(s.discrete.height);
          } else {
            line += " " + std::to_string(s.stepwise.min_width) + "x" + std::to_string(s.stepwise.min_height) + "-" +
                    std::to_string(s.stepwise.max_width) + "x" + std::to_string(s.stepwise.max_height);
            break;
          }
        }
        info.formats.push_back(line);
      }
    }
    api.Close(fd);
    devices.push_back(info);
  }
  return devices;
}

}  // namespace jgpm
