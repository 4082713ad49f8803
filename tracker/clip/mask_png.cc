#include "tracker/clip/mask_png.h"

#include <cctype>
#include <cstring>
#include <fstream>
#include <iterator>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <zlib.h>

#include "io/base/error.h"

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
  auto corrupt = [&source](const std::string& what) { ThrowInputError(source, "corrupt PNG (" + what + ")"); };
  // The chunks: each fits the file with a correct CRC; IHDR first, the IDATs together, IEND
  // last and after them (libpng prints its own line on anything else).
  size_t at = 8;
  bool first = true, seen_idat = false, idat_ended = false;
  std::vector<uint8_t> header, compressed;
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
    if (stored != computed) corrupt("chunk '" + type + "' at byte " + std::to_string(at) + " fails its CRC");
    for (const char c : type)
      if (!std::isalpha(static_cast<unsigned char>(c))) corrupt("a chunk type that is not 4 letters at byte " + std::to_string(at));
    // Critical chunks (capital first letter) must be known; others may be skipped.
    if (std::isupper(static_cast<unsigned char>(type[0])) && type != "IHDR" && type != "PLTE" && type != "IDAT" &&
        type != "IEND")
      corrupt("unknown critical chunk '" + type + "'");
    const uint8_t* data = &bytes[at + 8];
    if (first != (type == "IHDR")) corrupt(first ? "the first chunk is '" + type + "', not IHDR" : "a second IHDR");
    if (first) header.assign(data, data + length);
    if (type == "IDAT") {
      if (idat_ended) corrupt("IDAT chunks apart");
      seen_idat = true;
      compressed.insert(compressed.end(), data, data + length);
    } else if (seen_idat) {
      idat_ended = true;
    }
    if (type == "PLTE" && seen_idat) corrupt("PLTE after the image data");
    first = false;
    at += 12 + length;
    if (type == "IEND") break;
  }
  if (at != bytes.size()) corrupt(std::to_string(bytes.size() - at) + " bytes after the IEND chunk");
  if (!seen_idat) corrupt("no image data");

  // The header: a size, and a bit depth the colour type allows.
  if (header.size() != 13) corrupt("IHDR of " + std::to_string(header.size()) + " bytes, not 13");
  const uint32_t width = BigEndian(&header[0]), height = BigEndian(&header[4]);
  const int depth = header[8], colour = header[9];
  if (width == 0 || height == 0 || width > 65535 || height > 65535)
    corrupt("image size " + std::to_string(width) + "x" + std::to_string(height));
  const int channels = colour == 0 ? 1 : colour == 2 ? 3 : colour == 3 ? 1 : colour == 4 ? 2 : colour == 6 ? 4 : 0;
  const bool depth_ok = colour == 0   ? (depth == 1 || depth == 2 || depth == 4 || depth == 8 || depth == 16)
                        : colour == 3 ? (depth == 1 || depth == 2 || depth == 4 || depth == 8)
                                      : (depth == 8 || depth == 16);
  if (channels == 0 || !depth_ok) corrupt("colour type " + std::to_string(colour) + " with bit depth " + std::to_string(depth));
  if (header[10] != 0 || header[11] != 0 || header[12] > 1) corrupt("unknown compression, filter or interlace method");

  // The image data: one zlib stream that inflates to exactly the rows the header implies
  // (each a filter byte 0-4 and its pixels), per Adam7 pass when interlaced.
  struct Pass {
    uint32_t x0, y0, dx, dy;
  };
  static const Pass kWhole[1] = {{0, 0, 1, 1}};
  static const Pass kAdam7[7] = {{0, 0, 8, 8}, {4, 0, 8, 8}, {0, 4, 4, 8}, {2, 0, 4, 4},
                                 {0, 2, 2, 4}, {1, 0, 2, 2}, {0, 1, 1, 2}};
  const Pass* passes = header[12] ? kAdam7 : kWhole;
  std::vector<std::pair<uint64_t, uint64_t>> rows;  // per pass: rows, bytes per row with the filter byte
  uint64_t expected = 0;
  for (int p = 0; p < (header[12] ? 7 : 1); ++p) {
    const uint64_t w = width > passes[p].x0 ? (width - passes[p].x0 + passes[p].dx - 1) / passes[p].dx : 0;
    const uint64_t h = height > passes[p].y0 ? (height - passes[p].y0 + passes[p].dy - 1) / passes[p].dy : 0;
    if (w == 0 || h == 0) continue;
    rows.push_back({h, 1 + (w * channels * depth + 7) / 8});
    expected += h * rows.back().second;
  }
  if (expected > (uint64_t{1} << 28))
    corrupt(std::to_string(width) + "x" + std::to_string(height) + " pixels, too large for a mask");
  std::vector<uint8_t> raw(expected + 1);
  z_stream z{};
  if (inflateInit(&z) != Z_OK) corrupt("zlib could not start");
  z.next_in = compressed.data();
  z.avail_in = static_cast<uInt>(compressed.size());
  z.next_out = raw.data();
  z.avail_out = static_cast<uInt>(raw.size());
  const int status = inflate(&z, Z_FINISH);
  const uint64_t produced = z.total_out;
  inflateEnd(&z);
  if (status != Z_STREAM_END) corrupt("the image data is not a complete zlib stream");
  if (produced != expected)
    corrupt("the image data holds " + std::to_string(produced) + " bytes, the header implies " + std::to_string(expected));
  uint64_t offset = 0;
  for (const auto& [count, stride] : rows) {
    for (uint64_t r = 0; r < count; ++r, offset += stride)
      if (raw[offset] > 4) corrupt("row filter " + std::to_string(raw[offset]));
  }
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
