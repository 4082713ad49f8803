// A folder of results that appears whole or not at all: written as `DIR.partial`, renamed
// to DIR by Commit(). DIR must not exist or be empty; an existing DIR.partial belongs to
// another writer (or one that was stopped) and is refused, never removed. If the object
// is destroyed before Commit (an exception on the way), the partial folder is removed.
#pragma once

#include <filesystem>

namespace jgpm {

class OutputFolder {
 public:
  // Creates DIR.partial (and DIR's parent folders). InputError naming the folder when DIR
  // exists and is not an empty folder, or DIR.partial exists, or it cannot be created.
  explicit OutputFolder(const std::filesystem::path& dir);
  ~OutputFolder();
  OutputFolder(const OutputFolder&) = delete;
  OutputFolder& operator=(const OutputFolder&) = delete;

  // Where to write the files meanwhile.
  const std::filesystem::path& partial() const { return partial_; }
  const std::filesystem::path& dir() const { return dir_; }
  // Moves the folder into place. InputError if that fails (the partial folder is removed).
  void Commit();

 private:
  std::filesystem::path dir_, partial_;
  bool done_ = false;
};

}  // namespace jgpm
