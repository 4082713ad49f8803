// Writing the pictures of the prior layer (latent plots, validation charts, stick
// figures): PNG-encoded, then written atomically.
#pragma once

#include <filesystem>

#include <opencv2/core.hpp>

namespace jgpm {

// InputError naming `path` if the image cannot be encoded or written.
void WritePngFile(const std::filesystem::path& path, const cv::Mat& image);

}  // namespace jgpm
