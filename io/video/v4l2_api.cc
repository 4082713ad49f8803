#include "io/video/v4l2_api.h"

#include <libv4l2.h>
#include <poll.h>
#include <sys/mman.h>

namespace jgpm {

int LibV4l2Api::Stat(const std::string& path, struct stat* st) { return ::stat(path.c_str(), st); }
int LibV4l2Api::Open(const std::string& path, int flags) { return v4l2_open(path.c_str(), flags); }
int LibV4l2Api::Close(int fd) { return v4l2_close(fd); }
int LibV4l2Api::Ioctl(int fd, unsigned long request, void* arg) {
  int r;
  do {
    r = v4l2_ioctl(fd, request, arg);
  } while (r < 0 && errno == EINTR);
  return r;
}
void* LibV4l2Api::Mmap(size_t length, int fd, int64_t offset) {
  return v4l2_mmap(nullptr, length, PROT_READ | PROT_WRITE, MAP_SHARED, fd, offset);
}
int LibV4l2Api::Munmap(void* address, size_t length) { return v4l2_munmap(address, length); }
int LibV4l2Api::Poll(int fd, int timeout_ms, short* revents) {
  pollfd p{fd, POLLIN, 0};
  const int r = ::poll(&p, 1, timeout_ms);
  *revents = p.revents;
  return r;
}

}  // namespace jgpm
