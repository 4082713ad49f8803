// Where a real trial changes from one motion to another (issue #16): the events that cut
// motion A, the true transition and motion B from a single trial, located by a rule per
// kind so that the evaluation runs on any trial of the CMU layout, not only on listed
// frames. Every rule works on the trial's own forward kinematics (y is up):
//   start  the root's horizontal speed crosses speed_mps upward, having stayed below it for
//          hold_s and staying above it for hold_s after (a shuffle is not a start);
//   stop   the same, downward;
//   kick   the peak 3-D speed of either foot (the kicking foot moves fastest);
//   jump   the last frame on the floor before take-off: the first stretch of hold_air_s
//          with every foot point more than air_mm above the floor, then back to the last
//          frame whose lowest foot point was within contact_mm of it (the floor: the 5th
//          percentile of the lowest foot point over the trial); the flight must also
//          follow hold_air_s on the floor;
//   duck   the root's lowest point.
// Speeds and heights are smoothed first by a centred moving average of smoothing_s, as
// marker jitter would otherwise decide the crossings.
//
// The event list (datasets_scripts/transitions.txt): one event a line, `TRIAL KIND
// [@FRAME] [tune]`, '#' comments; @FRAME overrides the rule with a 120 fps frame number as
// the AMC file counts it; `tune` marks the events defaults may be tuned on (the others are
// reported, never tuned on).
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "io/mocap/motion.h"
#include "io/mocap/skeleton.h"

namespace jgpm {

enum class TransitionKind { kStart, kStop, kKick, kJump, kDuck };

// "start", "stop", "kick", "jump", "duck".
std::string_view TransitionKindName(TransitionKind kind);
// The inverse of TransitionKindName; false (kind untouched) for any other name.
bool ParseTransitionKind(std::string_view name, TransitionKind* kind);

struct TransitionRules {
  double speed_mps = 0.3;    // start/stop threshold on the root's horizontal speed
  double hold_s = 0.25;      // ... and how long it must stay past it
  double air_mm = 50;        // jump: every foot point this far above the floor is airborne
  double hold_air_s = 0.1;   // ... for at least this long
  double contact_mm = 25;    // jump: a foot point this near the floor is on it
  double smoothing_s = 0.1;  // centred moving average before every rule

  bool Check(std::string* why) const;
};

// The event's frame (0-based row of `motion`). InputError naming `source` when the
// trial has no such event (never started, no flight, no foot bones...).
int FindTransitionFrame(const Skeleton& skeleton, const Motion& motion, TransitionKind kind,
                        const TransitionRules& rules, const std::string& source);

struct TransitionEvent {
  std::string trial;               // e.g. "131_03"
  TransitionKind kind = TransitionKind::kStart;
  std::optional<int> frame_number;  // @FRAME: the AMC file's frame number, 120 fps
  bool tune = false;
  int line = 0;                     // in the list, for messages
};

// Parses an event list; InputError "source:line: ..." for a malformed trial id, an
// unknown kind, a bad @FRAME, an unknown word, or a list without events.
std::vector<TransitionEvent> ParseTransitionEvents(std::string_view text, const std::string& source);
std::vector<TransitionEvent> ReadTransitionEvents(const std::filesystem::path& path);

}  // namespace jgpm
