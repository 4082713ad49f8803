#include "io/base/png_file.h"

#include <string>
#include <vector>

#include <opencv2/imgcodecs.hpp>

#include "io/base/error.h"
#include "io/base/text_reader.h"

namespace jgpm {

std::string EncodePng(const cv::Mat& image, const std::string& source) {
  std::vector<uchar> bytes;
  if (!cv::imencode(".png", image, bytes)) ThrowInputError(source, "PNG encoding failed");
  return std::string(bytes.begin(), bytes.end());
}

void WritePngFile(const std::filesystem::path& path, const cv::Mat& image) {
  WriteFileAtomic(path, EncodePng(image, path.string()));
}

}  // namespace jgpm
