#include "tracker/mask_png.h"

#include <cstring>
#include <fstream>
#include <iterator>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <zlib.h>

#include "io/error.h"

namespace jgpm {
namespace {

uint32_t BigEndian(const uint8_t* p) {
  return (uint32_t{p[0]} << 24) | (uint32_t{p[1]} << 16) | (uint32_t{p[2]} << 8) | uint32_t{p[3]};
}

}  // namespace

void CheckPngFile(const std::vector<uint8_t>& bytes, const std::string& source) {
  static const uint8_t kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  if (bytes.size() < 8 || std::memcmp(bytes.data(), kSignature, 8) != 0)
    ThrowInputError(source, "not a PNG file (expected a mask PNG)");
  size_t at = 8;
  bool first = true;
  while (true) {
    if (bytes.size() - at < 12)
      ThrowInputError(source, "truncated PNG (ends at byte " + std::to_string(bytes.size()) + " inside a chunk header)");
    const uint32_t length = BigEndian(&bytes[at]);
    const std::string type(reinterpret_cast<const char*>(&bytes[at + 4]), 4);
    if (length > bytes.size() - at - 12)
      ThrowInputError(source, "truncated PNG (chunk '" + type + "' at byte " + std::to_string(at) + " needs " +
                                  std::to_string(length) + " bytes, the file ends first)");
    const uint32_t stored = BigEndian(&bytes[at + 8 + length]);
    const uint32_t computed = static_cast<uint32_t>(crc32(crc32(0L, Z_NULL, 0), &bytes[at + 4], length + 4));
    if (stored != computed)
      ThrowInputError(source, "corrupt PNG (chunk '" + type + "' at byte " + std::to_string(at) + " fails its CRC)");
    if (first && type != "IHDR") ThrowInputError(source, "corrupt PNG (the first chunk is '" + type + "', not IHDR)");
    first = false;
    at += 12 + length;
    if (type == "IEND") break;
  }
  if (at != bytes.size())
    ThrowInputError(source, "corrupt PNG (" + std::to_string(bytes.size() - at) + " bytes after the IEND chunk)");
}

cv::Mat DecodeMaskPng(const std::vector<uint8_t>& bytes, const std::string& source, int width, int height) {
  CheckPngFile(bytes, source);
  cv::Mat image;
  try {
    image = cv::imdecode(bytes, cv::IMREAD_GRAYSCALE);
  } catch (const cv::Exception& e) {
    ThrowInputError(source, "cannot be decoded as a PNG (" + e.msg + ")");
  }
  if (image.empty()) ThrowInputError(source, "cannot be decoded as a PNG (expected a mask PNG)");
  if (image.cols != width || image.rows != height)
    ThrowInputError(source, "is " + std::to_string(image.cols) + "x" + std::to_string(image.rows) + ", expected " +
                                std::to_string(width) + "x" + std::to_string(height));
  cv::Mat mask;
  cv::threshold(image, mask, 127, 255, cv::THRESH_BINARY);
  return mask;
}

cv::Mat ReadMaskPng(const std::filesystem::path& path, int width, int height) {
  std::ifstream in(path, std::ios::binary);
  if (!in) ThrowInputError(path.string(), "missing or unreadable (expected a mask PNG)");
  const std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  return DecodeMaskPng(bytes, path.string(), width, height);
}

}  // namespace jgpm
