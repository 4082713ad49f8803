#include "io/base/mapped_file.h"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

namespace jgpm {

MappedFile::MappedFile(const std::string& path) {
  const int fd = open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return;
  struct stat status {};
  if (fstat(fd, &status) == 0 && S_ISREG(status.st_mode)) {
    size_ = static_cast<size_t>(status.st_size);
    if (size_ == 0) {
      ok_ = true;  // mmap refuses a length of 0
    } else {
      // MAP_POPULATE: the pages mapped in one call, not faulted in one by one as read.
      void* data = mmap(nullptr, size_, PROT_READ, MAP_PRIVATE | MAP_POPULATE, fd, 0);
      if (data != MAP_FAILED) {
        data_ = data;
        ok_ = true;
      } else {
        size_ = 0;
      }
    }
  }
  close(fd);  // the mapping outlives the descriptor
}

MappedFile::~MappedFile() {
  if (data_) munmap(data_, size_);
}

}  // namespace jgpm
