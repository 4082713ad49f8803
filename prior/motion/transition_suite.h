// The transition evaluation (`jgpm eval --suite transitions`, issue #16): real transitions
// cut from single trials and each method's transition measured against them.
//
// Per event (prior/motion/transition_event.h: the kind's rule, or @FRAME), per shift of the event by
// -4, 0, +4 frames at 30 fps and per N: the trial at 30 fps anchored on the event's frame;
// the true transition is the N frames starting N/2 before it (rounded down), motion A the
// 45 frames before those, motion B the 45 after. A case that does not fit in the trial is
// skipped and counted. Each method then fills the N frames from A and B alone
// (prior/motion/motion_transition.h), and is measured (prior/motion/transition_measures.h). The CSV's
// eq23_mm places the root as in the truth (root-aligned: the pose alone); eq23_world_mm
// keeps the method's own root path (linear for every method), as L2P does. The floor for
// foot skating is the truth's lowest foot point in the window. RI is run with
// `random_seeds` seeds and reported as their mean (and the spread of eq23_mm). The oracle
// is given the true transition; every other method only A and B.
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "prior/motion/motion_transition.h"
#include "prior/motion/transition_event.h"
#include "prior/motion/transition_measures.h"

namespace jgpm {

struct TransitionSuiteOptions {
  std::vector<int> frames = {5, 15, 30};     // N
  std::vector<int> shifts = {-4, 0, 4};      // of the event, frames at 30 fps
  std::vector<TransitionMethod> methods = {TransitionMethod::kLsopa,  TransitionMethod::kLinear,
                                           TransitionMethod::kRandom, TransitionMethod::kSlerp,
                                           TransitionMethod::kHold,   TransitionMethod::kOracle,
                                           TransitionMethod::kLsopaRetrained};
  int context = 45;                          // frames of A and of B
  int random_seeds = 20;                     // RI
  TransitionRules rules;
  MotionTransitionOptions transition;        // the methods' other options (N and method are set per case)
};

struct TransitionSuiteRow {
  std::string trial;
  TransitionKind kind = TransitionKind::kStart;
  bool tune = false;
  int event_frame = 0;   // the AMC file's frame number (120 fps)
  int shift = 0;
  int frames = 0;        // N
  TransitionMethod method = TransitionMethod::kLsopa;
  TransitionMeasures measures;  // RI: the mean over its seeds
  double eq23_std_mm = 0;       // RI: the spread of eq. 23 (root-aligned) over its seeds
  double seconds = 0;           // generating one transition (RI: the mean)
  double retrain_change_deg = 0, retrain_latent_shift = 0;  // lsopa-rt (MotionTransitionResult)
};

// For looking at: per event, at shift 0 and the middle N (else the first N that fits in
// the trial), the truth and each method from
// 8 frames before the transition to 8 after (RI: its first seed).
struct TransitionStrip {
  std::string trial;
  TransitionKind kind = TransitionKind::kStart;
  Skeleton skeleton;
  std::vector<std::pair<std::string, Motion>> motions;  // "truth", then each method's name
};

struct TransitionSuiteResult {
  std::vector<TransitionSuiteRow> rows;
  std::vector<TransitionStrip> strips;
  int skipped = 0;  // cases that did not fit in their trial
};

// Progress: cases done, cases in all, the case's label.
using TransitionSuiteProgress = std::function<void(int, int, const std::string&)>;

// InputError naming the trial for a missing file or an event its rule cannot find.
TransitionSuiteResult RunTransitionSuite(const std::vector<TransitionEvent>& events,
                                         const std::filesystem::path& data_root,
                                         const TransitionSuiteOptions& options,
                                         const TransitionSuiteProgress& progress = {});

// One CSV row per event, shift, N and method (header included).
std::string TransitionSuiteCsv(const TransitionSuiteResult& result);

}  // namespace jgpm
