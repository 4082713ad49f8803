// What `jgpm eval --suite transitions` reports beside transitions.csv (issue #16): the
// per-frame errors, paired bootstrap intervals of LSOPA against each other method, the
// per-frame error plots and the summary table. All on eq. 23 with the root placed as in
// the truth (the pose alone, TransitionSuiteRow's eq23_mm), tuning and reported events
// apart.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "prior/motion/transition_suite.h"

namespace jgpm {

// LSOPA minus one other method over the cases (event, shift, N) both have.
struct PairedInterval {
  std::string scope;   // "all", a kind ("kick") or an N ("N=15")
  TransitionMethod other = TransitionMethod::kLinear;
  int cases = 0, events = 0;
  double mean_mm = 0;               // mean of LSOPA - other
  double low_mm = 0, high_mm = 0;   // its 95% bootstrap interval
  int lsopa_lower = 0;              // cases where LSOPA's error is the lower
};

// Paired bootstrap: `resamples` times, events drawn with replacement (an event's shifts
// and N are not independent cases, so the event is the unit), the mean difference over
// the drawn events' cases; the 2.5 and 97.5 percentiles. Per scope "all", per kind and
// per N, for every method in the result other than LSOPA. Events with tune == `tune`.
std::vector<PairedInterval> LsopaIntervals(const TransitionSuiteResult& result, bool tune, int resamples = 10000,
                                           uint64_t seed = 1);
std::string PairedIntervalsCsv(const std::vector<PairedInterval>& intervals);

// One row per case, method and transition frame: eq23_mm and eq23_world_mm.
std::string TransitionPerFrameCsv(const TransitionSuiteResult& result);

// Mean error per transition frame over the cases of one kind and N (tune == `tune`), one
// line per method; an empty Mat when there is no such case.
cv::Mat PerFramePlot(const TransitionSuiteResult& result, TransitionKind kind, int frames, bool tune);

// A Markdown table: per kind and N, the cases and each method's mean error (the lowest
// in bold); empty when no event has tune == `tune`.
std::string TransitionSummaryTable(const TransitionSuiteResult& result, bool tune);

// A Markdown table of foot skating (m/s): per N, the truth's own and each method's mean
// over the cases; empty when no event has tune == `tune`.
std::string FootSkateTable(const TransitionSuiteResult& result, bool tune);

}  // namespace jgpm
