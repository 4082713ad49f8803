// Mask PNGs: a whole file decodes to the mask that was written; every truncation and every
// flipped byte is refused with an InputError naming the file, before libpng sees it.
#include "tracker/mask_png.h"

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "io/error.h"

namespace jgpm {
namespace {

std::vector<uint8_t> EncodedMask(cv::Mat* mask) {
  *mask = cv::Mat::zeros(24, 32, CV_8U);
  cv::circle(*mask, {15, 11}, 7, 255, cv::FILLED);
  std::vector<uint8_t> bytes;
  EXPECT_TRUE(cv::imencode(".png", *mask, bytes));
  return bytes;
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
