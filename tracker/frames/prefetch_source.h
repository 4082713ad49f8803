// A frame source read ahead on a thread of its own, so that decoding and background
// subtraction of the next frames overlap the tracking of this one (on a 4-camera
// 320x240 clip they were a fifth of the tracking loop's wall time, done while the
// tracker's threads waited). The frames are the inner source's, in its order, so a run
// tracks the same with or without it.
//
// For files and folders only: a live camera's frame read ahead would wait while the
// tracker works and come out older than the one the camera has by then.
#pragma once

#include <condition_variable>
#include <deque>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>

#include "tracker/frames/frame_source.h"

namespace jgpm {

class PrefetchSource : public FrameSource {
 public:
  // Starts reading `inner` (which must outlive this) at once, at most `depth` (>= 1) frames ahead. `lost`, when
  // given, is read on the reading thread after each frame (the inner source's count of lost
  // frames, which only that thread may touch while it runs); lost() is its value with the
  // frame last handed out.
  PrefetchSource(FrameSource* inner, int depth, std::function<int()> lost = {});
  ~PrefetchSource() override { Stop(); }
  PrefetchSource(const PrefetchSource&) = delete;
  PrefetchSource& operator=(const PrefetchSource&) = delete;

  const std::vector<Camera>& cameras() const override { return cameras_; }
  double fps() const override { return fps_; }
  int NumFrames() const override { return num_frames_; }
  double mask_scale(size_t camera) const override;
  // The inner source's next frame; its InputError is thrown here, after the frames read
  // before it.
  bool Next(Frame* frame) override;
  int lost() const { return lost_; }
  // Stops reading (after the frame being read) and waits for the thread: afterwards Next
  // hands out only what was read, and the inner source may be asked anything.
  void Stop();

 private:
  void Read();

  FrameSource* const inner_;
  const std::vector<Camera> cameras_;  // copies: the inner source's are read on its thread
  const double fps_;
  const int num_frames_;
  std::vector<double> mask_scales_;
  const size_t depth_;
  const std::function<int()> count_lost_;

  std::mutex mutex_;
  std::condition_variable changed_;
  struct Ahead {
    Frame frame;
    int lost = 0;
  };
  std::deque<Ahead> ahead_;
  bool ended_ = false;  // the inner source ended or threw (error_)
  bool stop_ = false;
  std::exception_ptr error_;
  int lost_ = 0;
  std::thread thread_;
};

}  // namespace jgpm
