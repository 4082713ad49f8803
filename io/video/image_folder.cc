#include "io/video/image_folder.h"

#include <cmath>

#include <opencv2/imgcodecs.hpp>

#include "io/base/error.h"
#include "io/video/image_list.h"

namespace jgpm {

ImageFolderSource::ImageFolderSource(const std::filesystem::path& folder, double fps)
    : name_(folder.string()), files_(ListImages(folder)), fps_(fps) {
  if (!(std::isfinite(fps) && fps > 0 && fps <= 1000)) {
    ThrowInputError("--fps", "expected the image folder's frame rate, a number in (0, 1000]");
  }
  if (files_.empty()) ThrowInputError(name_, "holds no images (.png, .jpg, .jpeg, .bmp, .tif, .tiff)");
  const cv::Mat first = Load(0);
  width_ = first.cols;
  height_ = first.rows;
}

cv::Mat ImageFolderSource::Load(size_t k) const {
  const std::string path = files_[k].string();
  cv::Mat image = cv::imread(path, cv::IMREAD_COLOR);
  if (image.empty()) ThrowInputError(path, "is not an image OpenCV can read (damaged, or not an image)");
  if (width_ > 0 && (image.cols != width_ || image.rows != height_)) {
    ThrowInputError(path, "is " + std::to_string(image.cols) + "x" + std::to_string(image.rows) +
                              " but the folder's first image is " + std::to_string(width_) + "x" +
                              std::to_string(height_) + " (all frames must have one size)");
  }
  return image;
}

bool ImageFolderSource::Read(Image* image) {
  if (next_ >= files_.size()) return false;
  image->bgr = Load(next_);
  image->index = static_cast<int>(next_);
  image->time_s = next_ / fps_;
  image->latency_ms = 0;
  ++next_;
  return true;
}

std::vector<cv::Mat> ImageFolderSource::Sample(int n) {
  std::vector<cv::Mat> images;
  for (int k : EvenSample(NumFrames(), n)) images.push_back(Load(k));
  return images;
}

}  // namespace jgpm
