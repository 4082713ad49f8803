#include "io/cli/process_clock.h"

#include <time.h>
#include <unistd.h>

#include <fstream>
#include <sstream>
#include <string>

namespace jgpm {

std::optional<double> SecondsSinceProcessStarted() {
  std::ifstream in("/proc/self/stat");
  std::string line;
  if (!std::getline(in, line)) return std::nullopt;
  // Field 2, the command name, is in parentheses and may hold spaces: count from the last ')'.
  const size_t close = line.rfind(')');
  if (close == std::string::npos) return std::nullopt;
  std::istringstream fields(line.substr(close + 1));
  std::string skipped;
  for (int field = 3; field < 22; ++field) fields >> skipped;
  unsigned long long started_ticks = 0;  // field 22: the start time, in clock ticks since boot
  const long ticks_per_second = sysconf(_SC_CLK_TCK);
  timespec now{};
  if (!(fields >> started_ticks) || ticks_per_second <= 0 || clock_gettime(CLOCK_BOOTTIME, &now) != 0)
    return std::nullopt;
  const double seconds = static_cast<double>(now.tv_sec) + 1e-9 * static_cast<double>(now.tv_nsec) -
                         static_cast<double>(started_ticks) / static_cast<double>(ticks_per_second);
  if (seconds < 0) return std::nullopt;
  return seconds;
}

}  // namespace jgpm
