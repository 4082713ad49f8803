// The images of a folder, for commands that read a sequence or a set of images (chessboard
// photos, image-folder video).
#pragma once

#include <filesystem>
#include <vector>

namespace jgpm {

// Files in `folder` whose extension (any case) is .png, .jpg, .jpeg, .bmp, .tif or .tiff,
// sorted by name. InputError naming the folder when it is missing or not a folder.
std::vector<std::filesystem::path> ListImages(const std::filesystem::path& folder);

}  // namespace jgpm
