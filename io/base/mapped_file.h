// A file's bytes mapped read-only, for large binary files read whole (a pose table is
// tens of MB). Mapped, the bytes are the page cache's own pages: reading the 68 MB ML-JGPM
// table into a string took 0.5 s on our 2-core machines, nearly all of it faulting in fresh
// pages for the copy, against 0.03 s to map it.
#pragma once

#include <string>
#include <string_view>

namespace jgpm {

class MappedFile {
 public:
  // The file at `path`; empty (bytes() of size 0, ok() false) when it cannot be opened or
  // mapped. An empty file is ok() with no bytes.
  explicit MappedFile(const std::string& path);
  ~MappedFile();
  MappedFile(const MappedFile&) = delete;
  MappedFile& operator=(const MappedFile&) = delete;

  bool ok() const { return ok_; }
  std::string_view bytes() const { return {static_cast<const char*>(data_), size_}; }

 private:
  void* data_ = nullptr;
  size_t size_ = 0;
  bool ok_ = false;
};

}  // namespace jgpm
