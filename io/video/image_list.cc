#include "io/video/image_list.h"

#include <algorithm>
#include <cctype>
#include <iterator>
#include <string>
#include <system_error>

#include "io/base/error.h"

namespace jgpm {
namespace fs = std::filesystem;

std::vector<fs::path> ListImages(const fs::path& folder) {
  static const char* const kExtensions[] = {".png", ".jpg", ".jpeg", ".bmp", ".tif", ".tiff"};
  std::error_code ec;
  if (!fs::is_directory(folder, ec)) ThrowInputError(folder.string(), "no such folder, expected a folder of images");
  std::vector<fs::path> paths;
  for (const fs::directory_entry& entry : fs::directory_iterator(folder, ec)) {
    if (!entry.is_regular_file(ec)) continue;
    std::string extension = entry.path().extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(), [](unsigned char c) { return std::tolower(c); });
    if (std::find(std::begin(kExtensions), std::end(kExtensions), extension) != std::end(kExtensions)) {
      paths.push_back(entry.path());
    }
  }
  if (ec) ThrowInputError(folder.string(), "cannot be listed (" + ec.message() + ")");
  std::sort(paths.begin(), paths.end());
  return paths;
}

}  // namespace jgpm
