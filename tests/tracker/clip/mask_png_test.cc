// Mask PNGs: a whole file decodes to the mask that was written; every truncation and every
// flipped byte is refused with an InputError naming the file, before libpng sees it.
#include "tracker/clip/mask_png.h"

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "io/base/error.h"
#include "test_support.h"
#include <zlib.h>

namespace jgpm {
namespace {

std::vector<uint8_t> EncodedMask(cv::Mat* mask) {
  *mask = cv::Mat::zeros(24, 32, CV_8U);
  cv::circle(*mask, {15, 11}, 7, 255, cv::FILLED);
  std::vector<uint8_t> bytes;
  EXPECT_TRUE(cv::imencode(".png", *mask, bytes));
  return bytes;
}

// A grey 8-bit PNG written by hand (chunks in `order`, Adam7 when `interlaced`), so that
// files with valid CRCs but a wrong structure can be made.
void Chunk(std::vector<uint8_t>* png, const std::string& type, const std::vector<uint8_t>& data) {
  const uint32_t n = static_cast<uint32_t>(data.size());
  for (int s = 24; s >= 0; s -= 8) png->push_back(static_cast<uint8_t>(n >> s));
  std::vector<uint8_t> body(type.begin(), type.end());
  body.insert(body.end(), data.begin(), data.end());
  png->insert(png->end(), body.begin(), body.end());
  const uint32_t crc = static_cast<uint32_t>(crc32(crc32(0L, Z_NULL, 0), body.data(), static_cast<uInt>(body.size())));
  for (int s = 24; s >= 0; s -= 8) png->push_back(static_cast<uint8_t>(crc >> s));
}
std::vector<uint8_t> HandMadePng(const cv::Mat& grey, bool interlaced, const std::string& order = "H D E",
                                 uint8_t filter = 0) {
  const int w = grey.cols, h = grey.rows;
  std::vector<uint8_t> raw;
  const int passes[7][4] = {{0, 0, 8, 8}, {4, 0, 8, 8}, {0, 4, 4, 8}, {2, 0, 4, 4}, {0, 2, 2, 4}, {1, 0, 2, 2}, {0, 1, 1, 2}};
  for (int p = 0; p < (interlaced ? 7 : 1); ++p) {
    const int x0 = interlaced ? passes[p][0] : 0, y0 = interlaced ? passes[p][1] : 0;
    const int dx = interlaced ? passes[p][2] : 1, dy = interlaced ? passes[p][3] : 1;
    if (x0 >= w || y0 >= h) continue;
    for (int y = y0; y < h; y += dy) {
      raw.push_back(filter);
      for (int x = x0; x < w; x += dx) raw.push_back(grey.at<uint8_t>(y, x));
    }
  }
  std::vector<uint8_t> idat(compressBound(static_cast<uLong>(raw.size())));
  uLongf size = static_cast<uLongf>(idat.size());
  EXPECT_EQ(compress(idat.data(), &size, raw.data(), static_cast<uLong>(raw.size())), Z_OK);
  idat.resize(size);
  const std::vector<uint8_t> ihdr = {0, 0, static_cast<uint8_t>(w >> 8), static_cast<uint8_t>(w), 0, 0,
                                     static_cast<uint8_t>(h >> 8), static_cast<uint8_t>(h), 8, 0, 0, 0,
                                     static_cast<uint8_t>(interlaced)};
  std::vector<uint8_t> png = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  for (const char c : order) {
    if (c == 'H') Chunk(&png, "IHDR", ihdr);
    if (c == 'D') Chunk(&png, "IDAT", idat);
    if (c == 'h') Chunk(&png, "IDAT", std::vector<uint8_t>(idat.begin(), idat.begin() + idat.size() / 2));
    if (c == 'i') Chunk(&png, "IDAT", std::vector<uint8_t>(idat.begin() + idat.size() / 2, idat.end()));
    if (c == 'T') Chunk(&png, "tEXt", {'a', 0, 'b'});
    if (c == 'X') Chunk(&png, "\xff\xff\xff\xff", {});  // its CRC is 0xffffffff, right
    if (c == 'C') Chunk(&png, "ABCD", {});
    if (c == 'E') Chunk(&png, "IEND", {});
  }
  return png;
}

TEST(MaskPng, HandMadeFilesPlainAndInterlacedDecode) {
  cv::Mat mask;
  EncodedMask(&mask);
  for (const bool interlaced : {false, true}) {
    for (const char* order : {"H D E", "H h i E", "H T D E", "H D T E"}) {
      const cv::Mat back = DecodeMaskPng(HandMadePng(mask, interlaced, order), "m.png", 32, 24);
      EXPECT_EQ(cv::countNonZero(back != mask), 0) << interlaced << " " << order;
    }
  }
}

// Found by tests/fuzz/mask_png_fuzzer: files whose CRCs are right but whose structure is
// not made libpng print its own line before ours.
TEST(MaskPng, ValidChunksInAWrongStructureAreRefused) {
  cv::Mat mask;
  EncodedMask(&mask);
  const struct {
    const char* order;
    uint8_t filter;
    const char* phrase;
  } cases[] = {{"H E", 0, "no image data"},        {"H h T i E", 0, "IDAT chunks apart"},
               {"H D H E", 0, "a second IHDR"},    {"D H E", 0, "not IHDR"},
               {"H h E", 0, "not a complete zlib"}, {"H D E", 7, "row filter 7"},
               {"H X D E", 0, "not 4 letters"},    {"H C D E", 0, "unknown critical chunk"}};
  for (const auto& c : cases) {
    test::ExpectInputError([&] { DecodeMaskPng(HandMadePng(mask, false, c.order, c.filter), "s.png", 32, 24); },
                           {"s.png: corrupt PNG", c.phrase});
  }
}

TEST(MaskPng, AWholeFileDecodesToTheMaskWritten) {
  cv::Mat mask;
  const std::vector<uint8_t> bytes = EncodedMask(&mask);
  const cv::Mat back = DecodeMaskPng(bytes, "m.png", 32, 24);
  EXPECT_EQ(cv::countNonZero(back != mask), 0);
  EXPECT_GT(cv::countNonZero(back), 100);
}

TEST(MaskPng, GreyLevelsAreThresholdedAtHalf) {
  cv::Mat grey(2, 2, CV_8U);
  grey.at<uint8_t>(0, 0) = 127, grey.at<uint8_t>(0, 1) = 128, grey.at<uint8_t>(1, 0) = 0, grey.at<uint8_t>(1, 1) = 200;
  std::vector<uint8_t> bytes;
  ASSERT_TRUE(cv::imencode(".png", grey, bytes));
  const cv::Mat mask = DecodeMaskPng(bytes, "g.png", 2, 2);
  EXPECT_EQ(mask.at<uint8_t>(0, 0), 0);
  EXPECT_EQ(mask.at<uint8_t>(0, 1), 255);
  EXPECT_EQ(mask.at<uint8_t>(1, 0), 0);
  EXPECT_EQ(mask.at<uint8_t>(1, 1), 255);
}

TEST(MaskPng, EveryTruncationIsRefusedNamingTheFile) {
  cv::Mat mask;
  const std::vector<uint8_t> bytes = EncodedMask(&mask);
  for (size_t size = 0; size < bytes.size(); ++size) {
    const std::vector<uint8_t> cut(bytes.begin(), bytes.begin() + size);
    try {
      DecodeMaskPng(cut, "cut.png", 32, 24);
      FAIL() << "a file cut to " << size << " of " << bytes.size() << " bytes was accepted";
    } catch (const InputError& e) {
      EXPECT_EQ(std::string(e.what()).rfind("cut.png: ", 0), 0u) << e.what();
    }
  }
}

TEST(MaskPng, EveryFlippedByteIsRefused) {
  cv::Mat mask;
  const std::vector<uint8_t> bytes = EncodedMask(&mask);
  for (size_t i = 0; i < bytes.size(); ++i) {
    std::vector<uint8_t> bad = bytes;
    bad[i] ^= 0x10;
    EXPECT_THROW(DecodeMaskPng(bad, "bad.png", 32, 24), InputError) << "byte " << i;
  }
}

TEST(MaskPng, WrongSizeAndTrailingBytesAndOtherFormatsAreRefused) {
  cv::Mat mask;
  std::vector<uint8_t> bytes = EncodedMask(&mask);
  EXPECT_THROW(DecodeMaskPng(bytes, "m.png", 24, 32), InputError);
  std::vector<uint8_t> longer = bytes;
  longer.push_back(0);
  EXPECT_THROW(DecodeMaskPng(longer, "m.png", 32, 24), InputError);
  std::vector<uint8_t> jpeg;
  ASSERT_TRUE(cv::imencode(".jpg", mask, jpeg));
  EXPECT_THROW(DecodeMaskPng(jpeg, "m.jpg", 32, 24), InputError);
  EXPECT_THROW(ReadMaskPng("/nonexistent/m.png", 32, 24), InputError);
}

}  // namespace
}  // namespace jgpm
