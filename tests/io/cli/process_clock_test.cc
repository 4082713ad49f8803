#include "io/cli/process_clock.h"

#include <chrono>
#include <thread>

#include <gtest/gtest.h>

namespace jgpm {
namespace {

// Taken while the test binary's statics are initialised, before main: the process started
// before this, so its age is at least the time since (to the clock's 10 ms steps).
const auto kLoaded = std::chrono::steady_clock::now();

double Since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

TEST(ProcessClock, CountsFromBeforeMainAndAdvancesWithTheWallClock) {
  const std::optional<double> first = SecondsSinceProcessStarted();
  ASSERT_TRUE(first.has_value()) << "/proc/self/stat unreadable";
  EXPECT_GE(*first, Since(kLoaded) - 0.011);
  EXPECT_LT(*first, 600.0);  // not the machine's uptime, nor another clock's zero
  const auto before = std::chrono::steady_clock::now();
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  const std::optional<double> second = SecondsSinceProcessStarted();
  ASSERT_TRUE(second.has_value());
  EXPECT_NEAR(*second - *first, Since(before), 0.03);
}

}  // namespace
}  // namespace jgpm
