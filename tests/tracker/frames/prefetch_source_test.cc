// The read-ahead source against the source it reads: the same frames in the same order,
// the lost-frame count that went with each, the inner source's error after the frames
// before it, and a stop that leaves no thread behind, also when the reader is blocked on a
// full queue.
#include "tracker/frames/prefetch_source.h"

#include <atomic>
#include <stdexcept>

#include <gtest/gtest.h>

#include "io/base/error.h"

namespace jgpm {
namespace {

// `frames` frames of one 8x6 camera, each mask filled with its index; frame `fail` (if
// >= 0) throws an InputError. Counts the frames read and "loses" every third.
class CountingSource : public FrameSource {
 public:
  explicit CountingSource(int frames, int fail = -1) : frames_(frames), fail_(fail) {
    cameras_ = {LookAtCamera("cam0", 8, 6, 10, Eigen::Vector3d(0, 1500, -4000), Eigen::Vector3d(0, 900, 0))};
  }
  const std::vector<Camera>& cameras() const override { return cameras_; }
  double fps() const override { return 25; }
  int NumFrames() const override { return frames_; }
  double mask_scale(size_t) const override { return 0.5; }
  bool Next(Frame* frame) override {
    if (read_ == frames_) return false;
    if (read_ == fail_) ThrowInputError("clip.avi", "frame " + std::to_string(read_) + " is damaged");
    frame->index = read_;
    frame->masks = {cv::Mat(6, 8, CV_8UC1, cv::Scalar(read_))};
    if (read_ % 3 == 2) ++lost_;
    ++read_;
    return true;
  }
  int lost() const { return lost_; }
  int read() const { return read_; }

 private:
  std::vector<Camera> cameras_;
  int frames_, fail_;
  std::atomic<int> read_{0};
  int lost_ = 0;
};

TEST(PrefetchSource, HandsOutTheInnerSourcesFramesInOrderWithTheirLostCounts) {
  CountingSource inner(40);
  PrefetchSource ahead(&inner, 2, [&inner] { return inner.lost(); });
  EXPECT_EQ(ahead.NumFrames(), 40);
  EXPECT_EQ(ahead.fps(), 25);
  EXPECT_EQ(ahead.mask_scale(0), 0.5);
  ASSERT_EQ(ahead.cameras().size(), 1u);
  Frame frame;
  for (int k = 0; k < 40; ++k) {
    ASSERT_TRUE(ahead.Next(&frame)) << k;
    EXPECT_EQ(frame.index, k);
    EXPECT_EQ(frame.masks.at(0).at<uint8_t>(3, 4), k);
    EXPECT_EQ(ahead.lost(), (k + 1) / 3);  // frames 2, 5, 8, ... were lost by then
  }
  EXPECT_FALSE(ahead.Next(&frame));
  EXPECT_FALSE(ahead.Next(&frame));  // and stays at the end
}

TEST(PrefetchSource, ThrowsTheInnerSourcesErrorAfterTheFramesBeforeIt) {
  CountingSource inner(40, 5);
  PrefetchSource ahead(&inner, 3);
  Frame frame;
  for (int k = 0; k < 5; ++k) {
    ASSERT_TRUE(ahead.Next(&frame));
    EXPECT_EQ(frame.index, k);
  }
  try {
    ahead.Next(&frame);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("clip.avi: frame 5 is damaged"), std::string::npos) << e.what();
  }
}

TEST(PrefetchSource, ReadsNoFurtherThanItsDepthAndStopsWhileBlocked) {
  CountingSource inner(1000);
  {
    PrefetchSource ahead(&inner, 2);
    Frame frame;
    ASSERT_TRUE(ahead.Next(&frame));
    // The reader fills its two places and waits; give it time to (wrongly) read on.
    for (int wait = 0; wait < 200 && inner.read() < 3; ++wait) std::this_thread::sleep_for(std::chrono::milliseconds(1));
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    EXPECT_EQ(inner.read(), 3);  // the one handed out and two ahead
    ahead.Stop();                // returns although the reader was waiting for room
    const int read = inner.read();
    int handed = 1;
    while (ahead.Next(&frame)) EXPECT_EQ(frame.index, handed++);
    EXPECT_EQ(handed, read);  // what was read is still handed out, then the end
  }
  {
    PrefetchSource unread(&inner, 2);  // destroyed without a frame asked for: no hang
  }
}

}  // namespace
}  // namespace jgpm
