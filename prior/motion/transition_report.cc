#include "prior/motion/transition_report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <random>
#include <set>
#include <sstream>
#include <tuple>

#include <opencv2/imgproc.hpp>

namespace jgpm {
namespace {

using CaseKey = std::tuple<std::string, TransitionKind, int, int, int>;  // trial, kind, event, shift, N
using EventKey = std::tuple<std::string, TransitionKind, int>;

CaseKey KeyOf(const TransitionSuiteRow& r) { return {r.trial, r.kind, r.event_frame, r.shift, r.frames}; }
EventKey EventOf(const TransitionSuiteRow& r) { return {r.trial, r.kind, r.event_frame}; }

// The methods in the order the result first holds them.
std::vector<TransitionMethod> MethodsOf(const TransitionSuiteResult& result) {
  std::vector<TransitionMethod> methods;
  for (const TransitionSuiteRow& r : result.rows) {
    if (std::find(methods.begin(), methods.end(), r.method) == methods.end()) methods.push_back(r.method);
  }
  return methods;
}

std::string Name(TransitionMethod method) { return std::string(TransitionMethodName(method)); }

cv::Scalar MethodColour(TransitionMethod method) {  // BGR
  switch (method) {
    case TransitionMethod::kLsopa: return {40, 40, 210};
    case TransitionMethod::kLinear: return {200, 120, 30};
    case TransitionMethod::kRandom: return {150, 150, 150};
    case TransitionMethod::kSlerp: return {40, 160, 40};
    case TransitionMethod::kHold: return {30, 170, 200};
    case TransitionMethod::kOracle: return {0, 0, 0};
    case TransitionMethod::kLsopaRetrained: return {170, 60, 170};
  }
  return {0, 0, 0};
}

struct Mean {
  double sum = 0;
  int n = 0;
  void Add(double v) { sum += v, ++n; }
  double value() const { return n ? sum / n : 0; }
};

std::string Format(const char* format, double value) {
  char text[32];
  std::snprintf(text, sizeof text, format, value);
  return text;
}

// A Markdown table's header: the leading columns, then one per method.
std::string HeaderRow(const std::vector<std::string>& leading, const std::vector<TransitionMethod>& methods) {
  std::string head = "|", rule = "|";
  for (const std::string& c : leading) head += " " + c + " |", rule += "---|";
  for (TransitionMethod m : methods) head += " " + Name(m) + " |", rule += "---|";
  return head + "\n" + rule + "\n";
}

PairedInterval Bootstrap(const std::map<EventKey, std::vector<double>>& diffs, int resamples, uint64_t seed) {
  PairedInterval out;
  std::vector<const std::vector<double>*> events;
  double sum = 0;
  for (const auto& [event, d] : diffs) {
    events.push_back(&d);
    for (double v : d) {
      sum += v;
      out.lsopa_lower += v < 0;
    }
    out.cases += static_cast<int>(d.size());
  }
  out.events = static_cast<int>(events.size());
  if (out.cases == 0) return out;
  out.mean_mm = sum / out.cases;
  std::mt19937_64 random(seed);
  std::uniform_int_distribution<size_t> pick(0, events.size() - 1);
  std::vector<double> means(resamples);
  for (double& mean : means) {
    double s = 0;
    int n = 0;
    for (size_t e = 0; e < events.size(); ++e) {
      const std::vector<double>& d = *events[pick(random)];
      for (double v : d) s += v;
      n += static_cast<int>(d.size());
    }
    mean = s / std::max(n, 1);
  }
  std::sort(means.begin(), means.end());
  const auto at = [&](double q) { return means[static_cast<size_t>(std::floor(q * (means.size() - 1)))]; };
  out.low_mm = at(0.025);
  out.high_mm = at(0.975);
  return out;
}

}  // namespace

std::vector<PairedInterval> LsopaIntervals(const TransitionSuiteResult& result, bool tune, int resamples,
                                           uint64_t seed) {
  std::map<CaseKey, double> lsopa;
  for (const TransitionSuiteRow& r : result.rows) {
    if (r.tune == tune && r.method == TransitionMethod::kLsopa) lsopa[KeyOf(r)] = r.measures.eq23_root_aligned_mean_mm;
  }
  std::vector<std::string> scopes = {"all"};
  std::set<TransitionKind> kinds;
  std::set<int> frames;
  for (const TransitionSuiteRow& r : result.rows) {
    if (r.tune != tune) continue;
    kinds.insert(r.kind);
    frames.insert(r.frames);
  }
  for (TransitionKind k : kinds) scopes.emplace_back(TransitionKindName(k));
  for (int n : frames) scopes.push_back("N=" + std::to_string(n));
  std::vector<PairedInterval> out;
  for (TransitionMethod other : MethodsOf(result)) {
    if (other == TransitionMethod::kLsopa) continue;
    for (const std::string& scope : scopes) {
      std::map<EventKey, std::vector<double>> diffs;
      for (const TransitionSuiteRow& r : result.rows) {
        if (r.tune != tune || r.method != other) continue;
        if (scope != "all" && scope != TransitionKindName(r.kind) && scope != "N=" + std::to_string(r.frames)) continue;
        const auto it = lsopa.find(KeyOf(r));
        if (it != lsopa.end()) diffs[EventOf(r)].push_back(it->second - r.measures.eq23_root_aligned_mean_mm);
      }
      if (diffs.empty()) continue;
      PairedInterval interval = Bootstrap(diffs, resamples, seed);
      interval.scope = scope;
      interval.other = other;
      out.push_back(interval);
    }
  }
  return out;
}

std::string PairedIntervalsCsv(const std::vector<PairedInterval>& intervals) {
  std::ostringstream csv;
  csv << "scope,other,cases,events,lsopa_minus_other_mm,low_mm,high_mm,lsopa_lower\n";
  char line[256];
  for (const PairedInterval& p : intervals) {
    std::snprintf(line, sizeof line, "%s,%s,%d,%d,%.3f,%.3f,%.3f,%d\n", p.scope.c_str(), Name(p.other).c_str(),
                  p.cases, p.events, p.mean_mm, p.low_mm, p.high_mm, p.lsopa_lower);
    csv << line;
  }
  return csv.str();
}

std::string TransitionPerFrameCsv(const TransitionSuiteResult& result) {
  std::ostringstream csv;
  csv << "trial,kind,tune,event_frame,shift,N,method,frame,eq23_mm,eq23_world_mm\n";
  char line[256];
  for (const TransitionSuiteRow& r : result.rows) {
    const TransitionMeasures& m = r.measures;
    for (size_t i = 0; i < m.eq23_root_aligned_mm.size(); ++i) {
      std::snprintf(line, sizeof line, "%s,%s,%s,%d,%d,%d,%s,%zu,%.3f,%.3f\n", r.trial.c_str(),
                    std::string(TransitionKindName(r.kind)).c_str(), r.tune ? "yes" : "no", r.event_frame, r.shift, r.frames,
                    Name(r.method).c_str(), i + 1, m.eq23_root_aligned_mm[i], m.eq23_mm[i]);
      csv << line;
    }
  }
  return csv.str();
}

cv::Mat PerFramePlot(const TransitionSuiteResult& result, TransitionKind kind, int frames, bool tune) {
  std::map<TransitionMethod, std::vector<double>> sum;
  std::map<TransitionMethod, int> count;
  for (const TransitionSuiteRow& r : result.rows) {
    if (r.tune != tune || r.kind != kind || r.frames != frames) continue;
    std::vector<double>& s = sum[r.method];
    s.resize(r.measures.eq23_root_aligned_mm.size(), 0.0);
    for (size_t i = 0; i < s.size(); ++i) s[i] += r.measures.eq23_root_aligned_mm[i];
    ++count[r.method];
  }
  if (sum.empty()) return {};
  double top = 1;
  for (auto& [method, s] : sum) {
    for (double& v : s) {
      v /= count[method];
      top = std::max(top, v);
    }
  }
  top = std::ceil(top / 50) * 50;
  const int width = 640, height = 400, left = 60, right = 130, upper = 40, lower = 50;
  cv::Mat image(height, width, CV_8UC3, cv::Scalar(255, 255, 255));
  const auto text = [&](const std::string& t, cv::Point at) {
    cv::putText(image, t, at, cv::FONT_HERSHEY_SIMPLEX, 0.45, {0, 0, 0}, 1, cv::LINE_AA);
  };
  const int plot_w = width - left - right, plot_h = height - upper - lower;
  const auto point = [&](double frame, double mm) {
    const double x = frames > 1 ? (frame - 1) / (frames - 1) : 0.5;
    return cv::Point(left + static_cast<int>(std::lround(x * plot_w)),
                     upper + plot_h - static_cast<int>(std::lround(plot_h * mm / top)));
  };
  for (int g = 0; g <= 5; ++g) {  // horizontal grid, mm
    const double mm = top * g / 5;
    cv::line(image, point(1, mm), point(frames, mm), {225, 225, 225}, 1);
    text(std::to_string(static_cast<int>(mm)), {8, point(1, mm).y + 4});
  }
  for (int f = 1; f <= frames; f += std::max(1, frames / 6)) text(std::to_string(f), {point(f, 0).x - 4, upper + plot_h + 18});
  text("transition frame (30 fps)", {left + plot_w / 2 - 80, height - 12});
  const int cases = count.begin()->second;
  text(std::string(TransitionKindName(kind)) + ", N = " + std::to_string(frames) + ", " + (tune ? "tuning" : "reported") +
           " events: mean eq. 23 (mm) of " + std::to_string(cases) + " case(s)",
       {left - 40, 24});
  // LSOPA last, on top (lsopa-rt usually lies under it).
  std::vector<std::pair<TransitionMethod, std::vector<double>>> lines(sum.begin(), sum.end());
  std::stable_partition(lines.begin(), lines.end(), [](const auto& l) { return l.first != TransitionMethod::kLsopa; });
  int legend = 0;
  for (const auto& [method, s] : lines) {
    const cv::Scalar colour = MethodColour(method);
    const int thickness = method == TransitionMethod::kLsopa ? 3 : 2;
    for (size_t i = 0; i + 1 < s.size(); ++i) {
      cv::line(image, point(i + 1, s[i]), point(i + 2, s[i + 1]), colour, thickness, cv::LINE_AA);
    }
    for (size_t i = 0; i < s.size(); ++i) cv::circle(image, point(i + 1, s[i]), 3, colour, cv::FILLED, cv::LINE_AA);
    const int y = upper + 12 + 22 * legend++;
    cv::line(image, {width - right + 12, y - 4}, {width - right + 40, y - 4}, colour, thickness, cv::LINE_AA);
    text(Name(method), {width - right + 46, y});
  }
  return image;
}

std::string TransitionSummaryTable(const TransitionSuiteResult& result, bool tune) {
  const std::vector<TransitionMethod> methods = MethodsOf(result);
  std::map<std::pair<TransitionKind, int>, std::map<TransitionMethod, Mean>> cells;  // (kind, N) -> method
  for (const TransitionSuiteRow& r : result.rows) {
    if (r.tune == tune) cells[{r.kind, r.frames}][r.method].Add(r.measures.eq23_root_aligned_mean_mm);
  }
  if (cells.empty()) return "";
  std::ostringstream table;
  table << HeaderRow({"kind", "N", "cases"}, methods);
  for (const auto& [key, by_method] : cells) {
    // The lowest of the methods that generate from A and B alone (the oracle sees the truth).
    double best = 1e300;
    for (const auto& [m, mean] : by_method) {
      if (m != TransitionMethod::kOracle) best = std::min(best, mean.value());
    }
    table << "| " << TransitionKindName(key.first) << " | " << key.second << " | " << by_method.begin()->second.n
          << " |";
    for (TransitionMethod m : methods) {
      const auto it = by_method.find(m);
      const bool bold = it != by_method.end() && m != TransitionMethod::kOracle && it->second.value() == best;
      table << ' ' << (bold ? "**" : "") << (it == by_method.end() ? "-" : Format("%.1f", it->second.value()))
            << (bold ? "**" : "") << " |";
    }
    table << '\n';
  }
  return table.str();
}

std::string FootSkateTable(const TransitionSuiteResult& result, bool tune) {
  const std::vector<TransitionMethod> methods = MethodsOf(result);
  std::map<int, std::map<TransitionMethod, Mean>> cells;  // N -> method
  std::map<int, Mean> truth;                              // N: the truth's own, once per case
  for (const TransitionSuiteRow& r : result.rows) {
    if (r.tune != tune) continue;
    cells[r.frames][r.method].Add(r.measures.foot_skate_mps);
    if (r.method == methods.front()) truth[r.frames].Add(r.measures.true_foot_skate_mps);
  }
  if (cells.empty()) return "";
  std::ostringstream table;
  table << HeaderRow({"N", "truth"}, methods);
  for (const auto& [n, by_method] : cells) {
    table << "| " << n << " | " << Format("%.2f", truth[n].value()) << " |";
    for (TransitionMethod m : methods) {
      const auto it = by_method.find(m);
      table << ' ' << (it == by_method.end() ? "-" : Format("%.2f", it->second.value())) << " |";
    }
    table << '\n';
  }
  return table.str();
}

}  // namespace jgpm
