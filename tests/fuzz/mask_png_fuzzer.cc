// libFuzzer target: DecodeMaskPng must either return a binary mask of the asked size or
// throw InputError, whatever the bytes; and every file OpenCV's decoder rejects must have
// been refused by the structural check first (else libpng prints a line of its own).
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "io/base/error.h"
#include "tracker/clip/mask_png.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::vector<uint8_t> bytes(data, data + size);
  try {
    const cv::Mat mask = jgpm::DecodeMaskPng(bytes, "fuzz.png", 32, 24);
    JGPM_CHECK(mask.cols == 32 && mask.rows == 24 && mask.type() == CV_8U);
    JGPM_CHECK(cv::countNonZero(mask) == cv::countNonZero(mask == 255));
  } catch (const jgpm::InputError& e) {
    JGPM_CHECK(std::string(e.what()).find("cannot be decoded") == std::string::npos);
  }
  return 0;
}
