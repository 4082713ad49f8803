// Several output files that appear together or not at all (a motion and its skeleton and
// picture, a CSV and its charts). Each file is written to a temporary beside its
// destination as it is added; Commit() renames them all into place. If the batch is
// destroyed before Commit (an exception on the way), the temporaries are removed and no
// existing file is touched. The renames themselves can only fail for reasons that would
// stop any writer (the folder vanished), after every byte is on disk.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace jgpm {

class OutputBatch {
 public:
  OutputBatch() = default;
  ~OutputBatch();
  OutputBatch(const OutputBatch&) = delete;
  OutputBatch& operator=(const OutputBatch&) = delete;

  // Writes `bytes` to a new temporary for `path`. InputError naming `path` when its folder
  // does not exist, it is a folder, it was added before, or the write fails.
  void Add(const std::filesystem::path& path, const std::string& bytes);
  // Moves every file into place, in the order added; returns their paths.
  std::vector<std::filesystem::path> Commit();

 private:
  struct Staged {
    std::filesystem::path temporary, path;
  };
  std::vector<Staged> staged_;
};

}  // namespace jgpm
