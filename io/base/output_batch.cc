#include "io/base/output_batch.h"

#include <system_error>

#include "io/base/error.h"
#include "io/base/text_reader.h"

namespace jgpm {
namespace fs = std::filesystem;

OutputBatch::~OutputBatch() {
  std::error_code ignored;
  for (const Staged& s : staged_) fs::remove(s.temporary, ignored);
}

void OutputBatch::Add(const fs::path& path, const std::string& bytes) {
  for (const Staged& s : staged_) {
    if (s.path == path) ThrowInputError(path.string(), "is written twice by one command");
  }
  staged_.push_back({WriteTemporaryBeside(path, bytes), path});
}

std::vector<fs::path> OutputBatch::Commit() {
  std::vector<fs::path> written;
  for (const Staged& s : staged_) {
    std::error_code ec;
    fs::rename(s.temporary, s.path, ec);
    if (ec) ThrowInputError(s.path.string(), "cannot replace file: " + ec.message());
    written.push_back(s.path);
  }
  staged_.clear();
  return written;
}

}  // namespace jgpm
