#include "io/cli/progress.h"

#include <cstdio>

#include <unistd.h>

namespace jgpm::cli {

using Clock = std::chrono::steady_clock;

ProgressLine::ProgressLine(std::string stage, double interval_s, double quiet_s)
    : stage_(std::move(stage)),
      interval_s_(interval_s),
      quiet_s_(quiet_s),
      tty_(isatty(fileno(stderr))),
      start_(Clock::now()) {}

void ProgressLine::Finish() {
  if (tty_ && shown_) std::fputc('\n', stderr);
  shown_ = false;
}

void ProgressLine::Update(double done, double total, const std::string& unit, const std::string& detail) {
  const auto now = Clock::now();
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  if (!counting_) counting_ = true, first_done_ = done, first_ = now;
  if (!tty_ && !shown_ && elapsed < quiet_s_) return;
  const bool open_ended = total < 0;  // a live source
  const bool last = !open_ended && done >= total;
  if (last && shown_done_ >= total) return;  // the end is shown once, however many reports reach it
  if (shown_ && !last && std::chrono::duration<double>(now - last_).count() < interval_s_) return;
  last_ = now;
  shown_ = true;
  shown_done_ = done;
  // The rate since the first report: what came before it (loading a model, building a
  // table, reading ahead) says nothing about how long the rest takes.
  const double counted_s = std::chrono::duration<double>(now - first_).count();
  const double rate = counted_s > 0 && done > first_done_ ? (done - first_done_) / counted_s : 0;
  if (open_ended) {
    std::fprintf(stderr, "%s %.0f %s%s%s  %.3g %s/s  %.0f s%s", stage_.c_str(), done, unit.c_str(),
                 detail.empty() ? "" : "  ", detail.c_str(), rate, unit.c_str(), elapsed, tty_ ? "   \r" : "\n");
    std::fflush(stderr);
    return;
  }
  if (rate <= 0) {  // nothing counted yet: no rate, no time left
    std::fprintf(stderr, "%s %.0f/%.0f %s%s%s  %.0f s%s", stage_.c_str(), done, total, unit.c_str(),
                 detail.empty() ? "" : "  ", detail.c_str(), elapsed, tty_ ? "   \r" : "\n");
  } else {
    std::fprintf(stderr, "%s %.0f/%.0f %s%s%s  %.3g %s/s  %.0f s, %.0f s left%s", stage_.c_str(), done, total,
                 unit.c_str(), detail.empty() ? "" : "  ", detail.c_str(), rate, unit.c_str(), elapsed,
                 (total - done) / rate, tty_ ? "   \r" : "\n");
  }
  std::fflush(stderr);
}

}  // namespace jgpm::cli
