// Writing pictures (latent plots, validation and benchmark charts, stick figures, the
// tracker's charts): PNG-encoded, then written atomically (alone, or in an OutputBatch).
#pragma once

#include <filesystem>
#include <string>

#include <opencv2/core.hpp>

namespace jgpm {

// The PNG file's bytes. InputError naming `source` if the image cannot be encoded.
std::string EncodePng(const cv::Mat& image, const std::string& source);
// InputError naming `path` if the image cannot be encoded or written.
void WritePngFile(const std::filesystem::path& path, const cv::Mat& image);

}  // namespace jgpm
