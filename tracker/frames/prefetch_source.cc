#include "tracker/frames/prefetch_source.h"

#include <algorithm>

namespace jgpm {

PrefetchSource::PrefetchSource(FrameSource* inner, int depth, std::function<int()> lost)
    : inner_(inner),
      cameras_(inner_->cameras()),
      fps_(inner_->fps()),
      num_frames_(inner_->NumFrames()),
      depth_(static_cast<size_t>(std::max(1, depth))),
      count_lost_(std::move(lost)) {
  for (size_t c = 0; c < cameras_.size(); ++c) mask_scales_.push_back(inner_->mask_scale(c));
  thread_ = std::thread([this] { Read(); });
}

void PrefetchSource::Stop() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  changed_.notify_all();
  if (thread_.joinable()) thread_.join();
}

double PrefetchSource::mask_scale(size_t camera) const {
  return camera < mask_scales_.size() ? mask_scales_[camera] : 1;
}

void PrefetchSource::Read() {
  for (;;) {
    {
      std::unique_lock<std::mutex> lock(mutex_);
      changed_.wait(lock, [this] { return stop_ || ahead_.size() < depth_; });
      if (stop_) {
        ended_ = true;
        return;
      }
    }
    Ahead next;
    bool more = false;
    std::exception_ptr error;
    try {
      more = inner_->Next(&next.frame);
      if (count_lost_) next.lost = count_lost_();
    } catch (...) {
      error = std::current_exception();
    }
    {
      std::lock_guard<std::mutex> lock(mutex_);
      if (more && !error) {
        ahead_.push_back(std::move(next));
      } else {
        ended_ = true;
        error_ = error;
      }
    }
    changed_.notify_all();
    if (!more || error) return;
  }
}

bool PrefetchSource::Next(Frame* frame) {
  std::unique_lock<std::mutex> lock(mutex_);
  changed_.wait(lock, [this] { return !ahead_.empty() || ended_; });
  if (ahead_.empty()) {
    if (error_) std::rethrow_exception(error_);
    return false;
  }
  *frame = std::move(ahead_.front().frame);
  lost_ = ahead_.front().lost;
  ahead_.pop_front();
  lock.unlock();
  changed_.notify_all();
  return true;
}

}  // namespace jgpm
