#include "prior/png_file.h"

#include <string>
#include <vector>

#include <opencv2/imgcodecs.hpp>

#include "io/error.h"
#include "io/text_reader.h"

namespace jgpm {

void WritePngFile(const std::filesystem::path& path, const cv::Mat& image) {
  std::vector<uchar> bytes;
  if (!cv::imencode(".png", image, bytes)) ThrowInputError(path.string(), "PNG encoding failed");
  WriteFileAtomic(path, std::string(bytes.begin(), bytes.end()));
}

}  // namespace jgpm
