// A folder of images (PNG, JPEG, BMP, TIFF; io/video/image_list.h) as a camera's image source, in
// name order at a frame rate the user gives (images carry no time). Files with other
// extensions are not frames and are ignored; a frame file that does not decode, or whose
// size differs from the first image's, stops the run with its name.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "io/video/image_source.h"

namespace jgpm {

class ImageFolderSource : public ImageSource {
 public:
  // InputError naming the folder (missing, no images) or the first image (unreadable), or
  // `--fps` when fps is not a positive finite number.
  ImageFolderSource(const std::filesystem::path& folder, double fps);

  const std::string& name() const override { return name_; }
  int width() const override { return width_; }
  int height() const override { return height_; }
  double fps() const override { return fps_; }
  int NumFrames() const override { return static_cast<int>(files_.size()); }
  // InputError naming the image that does not decode or has another size.
  bool Read(Image* image) override;
  std::vector<cv::Mat> Sample(int n) override;

 private:
  cv::Mat Load(size_t k) const;

  std::string name_;
  std::vector<std::filesystem::path> files_;
  double fps_;
  int width_ = 0, height_ = 0;
  size_t next_ = 0;
};

}  // namespace jgpm
