// The progress line's rate and time left count from its first report, not from when the
// line was made: a job whose setup takes long (loading a model, building a pose table)
// used to show, at its first frame, a rate of a third of a frame a second and a time left
// of hundreds of times the truth. Oracle: the sleeps between reports. The end is shown
// once, however many reports reach it.
#include "io/cli/progress.h"

#include <chrono>
#include <cstdio>
#include <string>
#include <thread>

#include <gtest/gtest.h>

namespace jgpm::cli {
namespace {

// The number before " s left" in the last line of `text` (-1 when the line has none).
double SecondsLeft(const std::string& text) {
  const size_t at = text.rfind(" s left");
  if (at == std::string::npos) return -1;
  const size_t start = text.rfind(' ', at - 1) + 1;
  return std::stod(text.substr(start, at - start));
}

TEST(ProgressLine, CountsFromTheFirstReportNotTheSetup) {
  testing::internal::CaptureStderr();
  {
    ProgressLine line("track", 0, 0);
    std::this_thread::sleep_for(std::chrono::milliseconds(600));  // setup
    line.Update(1, 101, "frames");
    const std::string first = testing::internal::GetCapturedStderr();
    EXPECT_EQ(SecondsLeft(first), -1) << first;  // nothing counted yet: no time left
    testing::internal::CaptureStderr();
    std::this_thread::sleep_for(std::chrono::milliseconds(50));  // one frame: 100 more take about 5 s
    line.Update(2, 101, "frames");
  }
  const std::string second = testing::internal::GetCapturedStderr();
  const double left = SecondsLeft(second);
  EXPECT_GT(left, 2) << second;
  EXPECT_LT(left, 20) << second;  // counted from construction: 99 / (2 / 0.65 s) = 32 s
}

// A tracker reads its last frame, then gives the frames it held: every one of those reports
// is at the total, and the log showed the last line as many times.
TEST(ProgressLine, ShowsTheEndOnce) {
  testing::internal::CaptureStderr();
  {
    ProgressLine line("track", 0, 0);
    line.Update(9, 10, "frames");
    for (int held = 0; held < 3; ++held) line.Update(10, 10, "frames");
  }
  const std::string text = testing::internal::GetCapturedStderr();
  size_t ends = 0;
  for (size_t at = text.find("10/10"); at != std::string::npos; at = text.find("10/10", at + 1)) ++ends;
  EXPECT_EQ(ends, 1u) << text;
}

}  // namespace
}  // namespace jgpm::cli
