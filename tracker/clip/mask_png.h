// Foreground masks stored as PNG files (the clip format's masks, and any mask folder).
// OpenCV's decoder lets libpng print to stderr and returns an empty image for a truncated
// or corrupt file, so a damaged mask would give a second, foreign error line. The file's
// chunk structure and every chunk's CRC are checked first, so such a file gets one
// InputError naming it and what is wrong.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <opencv2/core/mat.hpp>

namespace jgpm {

// Checks that `bytes` is a whole PNG file: the signature, chunks that fit the file with
// correct CRCs, IHDR first and IEND last. Throws InputError("<source>: ...") otherwise.
void CheckPngFile(const std::vector<uint8_t>& bytes, const std::string& source);

// Decodes a checked PNG as a binary mask (0 or 255; grey levels above 127 are foreground)
// of width x height pixels.
cv::Mat DecodeMaskPng(const std::vector<uint8_t>& bytes, const std::string& source, int width, int height);

// Reads and decodes the mask PNG at `path`.
cv::Mat ReadMaskPng(const std::filesystem::path& path, int width, int height);

}  // namespace jgpm
