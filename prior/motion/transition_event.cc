#include "prior/motion/transition_event.h"

#include <algorithm>
#include <cmath>

#include "io/base/enum_name.h"
#include "io/base/error.h"
#include "io/base/text_reader.h"
#include "io/gait/split.h"
#include "io/mocap/kinematics.h"

namespace jgpm {
namespace {

// Centred moving average over `window` samples (odd), shrinking at the ends.
std::vector<double> Smooth(const std::vector<double>& v, int window) {
  const int n = static_cast<int>(v.size()), half = window / 2;
  std::vector<double> prefix(n + 1, 0.0), out(n);
  for (int i = 0; i < n; ++i) prefix[i + 1] = prefix[i] + v[i];
  for (int i = 0; i < n; ++i) {
    const int lo = std::max(0, i - half), hi = std::min(n, i + half + 1);
    out[i] = (prefix[hi] - prefix[lo]) / (hi - lo);
  }
  return out;
}

// Speed (m/s) of a point track by central differences (one-sided at the ends).
std::vector<double> Speed(const std::vector<Eigen::Vector3d>& p, double fps, bool horizontal) {
  const int n = static_cast<int>(p.size());
  std::vector<double> speed(n, 0.0);
  for (int i = 0; i < n; ++i) {
    const int a = std::max(0, i - 1), b = std::min(n - 1, i + 1);
    if (a == b) continue;
    Eigen::Vector3d d = (p[b] - p[a]) / (b - a);
    if (horizontal) d.y() = 0;
    speed[i] = d.norm() * fps / 1000;  // mm per frame -> m/s
  }
  return speed;
}

// First frame i where the value crosses the threshold in the given direction and stays
// past it for `hold` frames, having stayed short of it for the `hold` frames before (a
// change from one steady state to the other); -1 if none.
int HeldCrossing(const std::vector<double>& v, double threshold, bool upward, int hold) {
  const int n = static_cast<int>(v.size());
  auto past = [&](int i) { return upward ? v[i] >= threshold : v[i] < threshold; };
  for (int i = std::max(1, hold); i + hold <= n; ++i) {
    if (past(i - 1) || !past(i)) continue;
    bool held = true;
    for (int k = 1; k < hold && held; ++k) held = past(i + k) && !past(i - 1 - k);
    if (held) return i;
  }
  return -1;
}

}  // namespace

std::string_view TransitionKindName(TransitionKind kind) {
  switch (kind) {
    case TransitionKind::kStart: return "start";
    case TransitionKind::kStop: return "stop";
    case TransitionKind::kKick: return "kick";
    case TransitionKind::kJump: return "jump";
    case TransitionKind::kDuck: return "duck";
  }
  return "?";
}

bool ParseTransitionKind(std::string_view name, TransitionKind* kind) {
  return ParseByName(name,
                     {TransitionKind::kStart, TransitionKind::kStop, TransitionKind::kKick, TransitionKind::kJump,
                      TransitionKind::kDuck},
                     TransitionKindName, kind);
}

bool TransitionRules::Check(std::string* why) const {
  const char* problem = nullptr;
  if (!(speed_mps > 0 && std::isfinite(speed_mps))) problem = "speed_mps must be > 0";
  else if (!(hold_s >= 0 && std::isfinite(hold_s))) problem = "hold_s must be >= 0";
  else if (!(air_mm > 0 && std::isfinite(air_mm))) problem = "air_mm must be > 0";
  else if (!(hold_air_s >= 0 && std::isfinite(hold_air_s))) problem = "hold_air_s must be >= 0";
  else if (!(contact_mm >= 0 && contact_mm < air_mm)) problem = "contact_mm must be in [0, air_mm)";
  else if (!(smoothing_s >= 0 && std::isfinite(smoothing_s))) problem = "smoothing_s must be >= 0";
  if (problem && why) *why = problem;
  return problem == nullptr;
}

int FindTransitionFrame(const Skeleton& skeleton, const Motion& motion, TransitionKind kind,
                        const TransitionRules& rules, const std::string& source) {
  std::string why;
  if (!rules.Check(&why)) ThrowInputError("transition rules", why);
  const int n = motion.NumFrames();
  const double fps = motion.frames_per_second;
  if (n < 3) ThrowInputError(source, "has " + std::to_string(n) + " frames; an event needs at least 3");
  if (!motion.values.allFinite()) ThrowInputError(source, "holds a non-finite value");
  auto frames = [&](double seconds) { return std::max(1, static_cast<int>(std::lround(seconds * fps))); };
  const int window = 2 * (frames(rules.smoothing_s) / 2) + 1;

  const std::vector<int> feet = skeleton.FootBones();
  if ((kind == TransitionKind::kKick || kind == TransitionKind::kJump) && feet.size() < 2) {
    ThrowInputError(source, "a " + std::string(TransitionKindName(kind)) +
                                " needs the skeleton's feet (lfoot and rfoot bones), which it lacks");
  }

  const Kinematics kinematics(skeleton);
  std::vector<Eigen::Vector3d> root(n);
  std::vector<std::vector<Eigen::Vector3d>> foot(feet.size(), std::vector<Eigen::Vector3d>(n));
  Eigen::Matrix3Xd joints;
  for (int f = 0; f < n; ++f) {
    kinematics.Compute(motion.Frame(f), &joints);
    root[f] = joints.col(0);
    for (size_t k = 0; k < feet.size(); ++k) foot[k][f] = joints.col(feet[k]);
  }

  const std::string what = std::string(TransitionKindName(kind));
  switch (kind) {
    case TransitionKind::kStart:
    case TransitionKind::kStop: {
      const std::vector<double> speed = Smooth(Speed(root, fps, true), window);
      const int at = HeldCrossing(speed, rules.speed_mps, kind == TransitionKind::kStart, frames(rules.hold_s));
      if (at < 0) {
        ThrowInputError(source, "has no " + what + ": the root's speed never crosses " +
                                    FormatShortest(rules.speed_mps) + " m/s " +
                                    (kind == TransitionKind::kStart ? "upward" : "downward") + " and stays past it for " +
                                    FormatShortest(rules.hold_s) + " s");
      }
      return at;
    }
    case TransitionKind::kKick: {
      int best = -1;
      double peak = -1;
      for (const auto& track : foot) {
        const std::vector<double> speed = Smooth(Speed(track, fps, false), window);
        const auto it = std::max_element(speed.begin(), speed.end());
        if (*it > peak) peak = *it, best = static_cast<int>(it - speed.begin());
      }
      return best;
    }
    case TransitionKind::kJump: {
      std::vector<double> lowest(n);
      for (int f = 0; f < n; ++f) {
        lowest[f] = foot[0][f].y();
        for (const auto& track : foot) lowest[f] = std::min(lowest[f], track[f].y());
      }
      // Flight is found on smoothed heights (jitter must not make a flight), the take-off
      // frame on raw ones (smoothing would move it earlier).
      const std::vector<double> smooth = Smooth(lowest, window);
      std::vector<double> sorted = smooth;
      const size_t k = sorted.size() / 20;  // 5th percentile
      std::nth_element(sorted.begin(), sorted.begin() + k, sorted.end());
      const double floor = sorted[k];
      std::vector<double> height(n);
      for (int f = 0; f < n; ++f) height[f] = smooth[f] - floor;
      const int up = HeldCrossing(height, rules.air_mm, true, frames(rules.hold_air_s));
      if (up < 0) {
        ThrowInputError(source, "has no jump: the feet never stay " + FormatShortest(rules.air_mm) +
                                    " mm above the floor for " + FormatShortest(rules.hold_air_s) + " s");
      }
      int at = up - 1;
      while (at > 0 && lowest[at] - floor > rules.contact_mm) --at;
      return at;
    }
    case TransitionKind::kDuck: {
      std::vector<double> height(n);
      for (int f = 0; f < n; ++f) height[f] = root[f].y();
      height = Smooth(height, window);
      return static_cast<int>(std::min_element(height.begin(), height.end()) - height.begin());
    }
  }
  return -1;
}

std::vector<TransitionEvent> ParseTransitionEvents(std::string_view text, const std::string& source) {
  LineReader in(text, source);
  std::vector<TransitionEvent> events;
  while (in.Next()) {
    std::string_view line = in.line();
    line = line.substr(0, line.find('#'));
    const auto tokens = SplitBlanks(line);
    if (tokens.empty()) continue;
    if (tokens.size() < 2) in.Fail("expected TRIAL KIND [@FRAME] [tune], found one word");
    TransitionEvent event;
    TrialId id;
    if (!ParseTrialId(std::string(tokens[0]), &id)) in.Fail("expected a trial id such as 131_03, found " + Quote(tokens[0]));
    event.trial = id.name;
    if (!ParseTransitionKind(tokens[1], &event.kind)) {
      in.Fail("expected an event kind (start, stop, kick, jump, duck), found " + Quote(tokens[1]));
    }
    event.line = in.line_number();
    for (size_t t = 2; t < tokens.size(); ++t) {
      const std::string_view token = tokens[t];
      if (token == "tune" && !event.tune) {
        event.tune = true;
      } else if (token.size() > 1 && token[0] == '@' && !event.frame_number) {
        const int frame = in.ParseInt(token.substr(1), "@FRAME");
        if (frame < 1) in.Fail("@FRAME counts from 1 as AMC files do, found " + Quote(token));
        event.frame_number = frame;
      } else {
        in.Fail("expected @FRAME or tune (each once), found " + Quote(token));
      }
    }
    events.push_back(event);
  }
  if (events.empty()) ThrowInputError(source, "lists no events");
  return events;
}

std::vector<TransitionEvent> ReadTransitionEvents(const std::filesystem::path& path) {
  return ParseTransitionEvents(ReadTextFile(path, "a transition event list (TRIAL KIND [@FRAME] [tune] per line)"),
                               path.string());
}

}  // namespace jgpm
