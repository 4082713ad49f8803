// The system calls live capture makes (stat, open, ioctl, mmap, poll, close), behind an
// interface so that a scripted fake (io/video/fake_v4l2_device.h) can stand in for a camera: in
// tests, and to run the whole live path without one. Errors as the calls give them: -1
// (or MAP_FAILED) and errno.
#pragma once

#include <sys/stat.h>

#include <cstddef>
#include <cstdint>
#include <string>

namespace jgpm {

class V4l2Api {
 public:
  virtual ~V4l2Api() = default;
  virtual int Stat(const std::string& path, struct stat* st) = 0;
  virtual int Open(const std::string& path, int flags) = 0;
  virtual int Close(int fd) = 0;
  virtual int Ioctl(int fd, unsigned long request, void* arg) = 0;
  // PROT_READ | PROT_WRITE, MAP_SHARED, as V4L2 buffers are mapped.
  virtual void* Mmap(size_t length, int fd, int64_t offset) = 0;
  virtual int Munmap(void* address, size_t length) = 0;
  // Waits for POLLIN; `revents` gets what happened.
  virtual int Poll(int fd, int timeout_ms, short* revents) = 0;
};

// The real calls, through libv4l2 (which works around drivers' quirks).
class LibV4l2Api : public V4l2Api {
 public:
  int Stat(const std::string& path, struct stat* st) override;
  int Open(const std::string& path, int flags) override;
  int Close(int fd) override;
  int Ioctl(int fd, unsigned long request, void* arg) override;
  void* Mmap(size_t length, int fd, int64_t offset) override;
  int Munmap(void* address, size_t length) override;
  int Poll(int fd, int timeout_ms, short* revents) override;
};

}  // namespace jgpm
