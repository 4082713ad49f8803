// The one progress line of every long `jgpm` command, on stderr:
//   <stage> <done>/<total> <unit>  <detail>  <rate> <unit>/s  <elapsed> s, <left> s left
// rewritten in place on a terminal, else one line per report. Reports come at most every
// `interval_s` seconds (the first and the last always). Into a log (not a terminal), a job
// shows nothing in its first `quiet_s` seconds, so short runs and one-line errors stay
// clean. The rate and the time left count from the first report, so the setup before it
// does not count as work. A job that reaches its total before it is done (a tracker giving
// its held frames after the last is read) shows the end once.
#pragma once

#include <chrono>
#include <string>

namespace jgpm::cli {

class ProgressLine {
 public:
  explicit ProgressLine(std::string stage, double interval_s = 0.5, double quiet_s = 2.0);
  ~ProgressLine() { Finish(); }
  ProgressLine(const ProgressLine&) = delete;
  ProgressLine& operator=(const ProgressLine&) = delete;

  // total < 0: open-ended (a live source, or training, whose end is its convergence test),
  // shown without a total or time left.
  void Update(double done, double total, const std::string& unit, const std::string& detail = "");
  // Ends the line on a terminal (before other output follows).
  void Finish();

 private:
  std::string stage_;
  double interval_s_;
  double quiet_s_;
  bool tty_;
  bool shown_ = false;
  bool counting_ = false;  // the first report came: the rate counts from it
  double first_done_ = 0;
  double shown_done_ = -1;  // the last report shown's
  std::chrono::steady_clock::time_point start_, last_, first_;
};

}  // namespace jgpm::cli
