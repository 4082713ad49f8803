#include "io/base/output_folder.h"

#include <system_error>

#include "io/base/error.h"

namespace jgpm {
namespace fs = std::filesystem;

OutputFolder::OutputFolder(const fs::path& dir) {
  dir_ = dir.lexically_normal();
  if (!dir_.has_filename()) dir_ = dir_.parent_path();  // "DIR/"
  std::error_code ec;
  if (fs::exists(dir_, ec)) {
    if (!fs::is_directory(dir_, ec)) ThrowInputError(dir_.string(), "exists and is not a folder");
    if (!fs::is_empty(dir_, ec)) ThrowInputError(dir_.string(), "exists and is not empty (choose a new --out, or remove it)");
  }
  partial_ = dir_.string() + ".partial";
  if (partial_.has_parent_path()) fs::create_directories(partial_.parent_path(), ec);
  if (!fs::create_directory(partial_, ec)) {
    ThrowInputError(partial_.string(), ec ? "cannot create the folder (" + ec.message() + ")"
                                          : "exists: another run is writing here, or one was stopped; "
                                            "remove it if none is running");
  }
}

OutputFolder::~OutputFolder() {
  std::error_code ignored;
  if (!done_) fs::remove_all(partial_, ignored);
}

void OutputFolder::Commit() {
  std::error_code ec;
  fs::remove(dir_, ec);  // an empty folder, checked at the start
  fs::rename(partial_, dir_, ec);
  if (ec) ThrowInputError(dir_.string(), "cannot move the finished results into place (" + ec.message() + ")");
  done_ = true;
}

}  // namespace jgpm
