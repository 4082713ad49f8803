// The transition suite's report (prior/motion/transition_report.h) on hand-made results whose
// intervals, tables and per-frame rows can be worked out by hand.
#include "prior/motion/transition_report.h"

#include <sstream>

#include <gtest/gtest.h>

namespace jgpm {
namespace {

TransitionSuiteRow Row(const std::string& trial, TransitionKind kind, int shift, int n, TransitionMethod method,
                       double mm, bool tune = false) {
  TransitionSuiteRow r;
  r.trial = trial;
  r.kind = kind;
  r.tune = tune;
  r.event_frame = 100;
  r.shift = shift;
  r.frames = n;
  r.method = method;
  r.measures.eq23_root_aligned_mean_mm = mm;
  r.measures.eq23_root_aligned_mm.assign(n, mm);
  r.measures.eq23_mm.assign(n, mm + 1);
  return r;
}

const PairedInterval& Find(const std::vector<PairedInterval>& all, const std::string& scope, TransitionMethod other) {
  for (const PairedInterval& p : all) {
    if (p.scope == scope && p.other == other) return p;
  }
  ADD_FAILURE() << "no interval for " << scope;
  return all.front();
}

// Two events. Event "a" has two cases (shifts), LSOPA - LI = -4 and -2; event "b" one case,
// +3. Drawing events with replacement, the lowest possible mean is a's (-3) and the highest
// b's (+3), each drawn twice with probability 1/4 > 2.5%: the 95% interval is [-3, +3]
// exactly, the mean over cases (-4 - 2 + 3) / 3 = -1.
TEST(TransitionReport, PairedBootstrapResamplesEvents) {
  TransitionSuiteResult result;
  for (int shift : {0, 4}) {
    result.rows.push_back(Row("a", TransitionKind::kKick, shift, 5, TransitionMethod::kLsopa, 10));
    result.rows.push_back(Row("a", TransitionKind::kKick, shift, 5, TransitionMethod::kLinear, shift == 0 ? 14 : 12));
  }
  result.rows.push_back(Row("b", TransitionKind::kJump, 0, 5, TransitionMethod::kLsopa, 20));
  result.rows.push_back(Row("b", TransitionKind::kJump, 0, 5, TransitionMethod::kLinear, 17));
  result.rows.push_back(Row("t", TransitionKind::kJump, 0, 5, TransitionMethod::kLsopa, 99, true));  // tuning: apart
  result.rows.push_back(Row("t", TransitionKind::kJump, 0, 5, TransitionMethod::kLinear, 0, true));
  const std::vector<PairedInterval> intervals = LsopaIntervals(result, false, 4000, 3);
  const PairedInterval& all = Find(intervals, "all", TransitionMethod::kLinear);
  EXPECT_EQ(all.cases, 3);
  EXPECT_EQ(all.events, 2);
  EXPECT_NEAR(all.mean_mm, -1, 1e-12);
  EXPECT_NEAR(all.low_mm, -3, 1e-12);
  EXPECT_NEAR(all.high_mm, 3, 1e-12);
  EXPECT_EQ(all.lsopa_lower, 2);
  // One event in scope: every resample is that event, so the interval is a point.
  const PairedInterval& kick = Find(intervals, "kick", TransitionMethod::kLinear);
  EXPECT_EQ(kick.cases, 2);
  EXPECT_NEAR(kick.low_mm, -3, 1e-12);
  EXPECT_NEAR(kick.high_mm, -3, 1e-12);
  EXPECT_EQ(Find(intervals, "N=5", TransitionMethod::kLinear).cases, 3);
  const std::vector<PairedInterval> tuning = LsopaIntervals(result, true, 100);  // kept: Find returns into it
  EXPECT_NEAR(Find(tuning, "all", TransitionMethod::kLinear).mean_mm, 99, 1e-12);
  // The same seed, the same intervals.
  EXPECT_EQ(PairedIntervalsCsv(intervals), PairedIntervalsCsv(LsopaIntervals(result, false, 4000, 3)));
}

TEST(TransitionReport, TableBoldsTheLowestMethodThatDoesNotSeeTheTruth) {
  TransitionSuiteResult result;
  for (const auto& [trial, lsopa, slerp] : {std::tuple{"a", 30.0, 20.0}, std::tuple{"b", 10.0, 30.0}}) {
    result.rows.push_back(Row(trial, TransitionKind::kStart, 0, 15, TransitionMethod::kLsopa, lsopa));
    result.rows.push_back(Row(trial, TransitionKind::kStart, 0, 15, TransitionMethod::kSlerp, slerp));
    result.rows.push_back(Row(trial, TransitionKind::kStart, 0, 15, TransitionMethod::kOracle, 1));
  }
  const std::string table = TransitionSummaryTable(result, false);
  EXPECT_NE(table.find("| kind | N | cases | lsopa | slerp | oracle |"), std::string::npos) << table;
  EXPECT_NE(table.find("| start | 15 | 2 | **20.0** | 25.0 | 1.0 |"), std::string::npos) << table;
  EXPECT_TRUE(TransitionSummaryTable(result, true).empty());
  result.rows[0].measures.foot_skate_mps = 0.5;  // a's lsopa
  result.rows[0].measures.true_foot_skate_mps = 0.2;
  result.rows[3].measures.foot_skate_mps = 1.5;  // b's lsopa
  result.rows[3].measures.true_foot_skate_mps = 0.4;
  const std::string skate = FootSkateTable(result, false);
  EXPECT_NE(skate.find("| 15 | 0.30 | 1.00 | 0.00 | 0.00 |"), std::string::npos) << skate;
}

TEST(TransitionReport, PerFrameRowsAndPlot) {
  TransitionSuiteResult result;
  result.rows.push_back(Row("a", TransitionKind::kDuck, 0, 5, TransitionMethod::kLsopa, 40));
  result.rows.push_back(Row("a", TransitionKind::kDuck, 0, 5, TransitionMethod::kHold, 80));
  result.rows.push_back(Row("a", TransitionKind::kDuck, 0, 15, TransitionMethod::kHold, 80));
  std::istringstream csv(TransitionPerFrameCsv(result));
  std::string line;
  std::getline(csv, line);
  EXPECT_EQ(line, "trial,kind,tune,event_frame,shift,N,method,frame,eq23_mm,eq23_world_mm");
  int rows = 0;
  while (std::getline(csv, line)) ++rows;
  EXPECT_EQ(rows, 5 + 5 + 15);
  const cv::Mat plot = PerFramePlot(result, TransitionKind::kDuck, 5, false);
  ASSERT_FALSE(plot.empty());
  EXPECT_EQ(plot.type(), CV_8UC3);
  // LSOPA's line is drawn in its red, hold's in its own colour: both appear.
  const auto has = [&](cv::Vec3b colour) {
    for (int y = 0; y < plot.rows; ++y) {
      for (int x = 0; x < plot.cols; ++x) {
        if (plot.at<cv::Vec3b>(y, x) == colour) return true;
      }
    }
    return false;
  };
  EXPECT_TRUE(has({40, 40, 210}));
  EXPECT_TRUE(has({30, 170, 200}));
  EXPECT_TRUE(PerFramePlot(result, TransitionKind::kKick, 5, false).empty());
}

}  // namespace
}  // namespace jgpm
