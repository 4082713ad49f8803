#include "tracker/frames/occluder_masks.h"

#include <opencv2/imgcodecs.hpp>

#include "io/base/error.h"
#include "tracker/frames/working_resolution.h"

namespace jgpm {

cv::Mat ReadOccluderMask(const std::string& path, const Camera& camera) {
  const cv::Mat image = cv::imread(path, cv::IMREAD_UNCHANGED);
  if (image.empty()) ThrowInputError(path, "cannot read it as an image (expected a PNG, 255 where an occluder is)");
  if (image.cols != camera.width || image.rows != camera.height) {
    ThrowInputError(path, "is " + std::to_string(image.cols) + "x" + std::to_string(image.rows) + ", camera " +
                              camera.name + "'s images are " + std::to_string(camera.width) + "x" +
                              std::to_string(camera.height));
  }
  std::vector<cv::Mat> channels;
  cv::split(image, channels);
  // An alpha channel (grey + alpha, or BGRA: what paint programs export) is not paint: a
  // transparent pixel is unpainted whatever colour it stores.
  const bool alpha = channels.size() == 2 || channels.size() == 4;
  const size_t colours = alpha ? channels.size() - 1 : channels.size();
  cv::Mat painted = channels[0] != 0;
  for (size_t i = 1; i < colours; ++i) painted |= channels[i] != 0;
  if (alpha) painted &= channels.back() != 0;
  return painted;
}

OccludedSource::OccludedSource(std::unique_ptr<FrameSource> inner, std::vector<cv::Mat> paintings)
    : inner_(std::move(inner)), paintings_(std::move(paintings)), scaled_(paintings_.size()) {
  JGPM_CHECK(inner_ && paintings_.size() == inner_->cameras().size());
}

bool OccludedSource::Next(Frame* frame) {
  if (!inner_->Next(frame)) return false;
  if (frame->dropped) return true;
  frame->hidden.assign(frame->masks.size(), cv::Mat());
  for (size_t c = 0; c < frame->masks.size() && c < paintings_.size(); ++c) {
    if (paintings_[c].empty() || frame->masks[c].empty()) continue;
    if (scaled_[c].size() != frame->masks[c].size()) scaled_[c] = ScaleHidden(paintings_[c], frame->masks[c].size());
    frame->hidden[c] = scaled_[c].clone();  // the frame's own: others draw on theirs
  }
  return true;
}

}  // namespace jgpm
