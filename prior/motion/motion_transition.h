// A transition between two recorded motions, as animators use it (`jgpm transition`,
// issue #16): motion A's end and motion B's start, resampled to 30 fps, joined by N
// generated frames, written as one motion on A's skeleton.
//
// - Both motions are taken every k-th frame (k = their rate / 30, which must be a whole
//   number; CMU's 120 fps gives 4), A ending on its last frame, B starting on its first.
// - B on A's skeleton: B's channels are matched to A's by name ("lfemur.rx"); a channel A
//   has and B lacks is refused. Different subjects keep their own angles on A's bones
//   (the summary says so).
// - LSOPA, LI and RI (prior/motion/transition.h) learn one GPDM on the last T frames of A and the
//   first T of B (T = the shorter of the two, at most `context`), as gait poses
//   (io/gait/gait_pose.h): A's last heading taken out of A, B's first out of B (the GPDM models
//   the body, not where it faces), each channel unwrapped along A then B; the generated
//   poses go back to frames turning evenly from the one heading to the other.
//   SLERP (prior/motion/slerp_transition.h) works on the frames directly; hold repeats A's last
//   frame. The oracle (evaluation only) fits the GPDM's latent points to the true
//   transition's gait poses, taken with the same headings; lsopa-rt is LSOPA followed by
//   Algorithm 1's retraining on [A; transition; B], its transition the new model's
//   (prior/motion/transition.h).
// - What the gait model does not carry is interpolated linearly between A's last frame and
//   B's first, for every method: the root's translation and heading (the GP generates the
//   body's angles, not travel or turning) and the channels outside the 18 gait joints
//   (clavicles, hands, fingers, toes).
#pragma once

#include <string>
#include <string_view>

#include "io/mocap/motion.h"
#include "io/mocap/skeleton.h"
#include "prior/motion/transition.h"

namespace jgpm {

enum class TransitionMethod { kLsopa, kLinear, kRandom, kSlerp, kHold, kOracle, kLsopaRetrained };
// "lsopa", "li", "ri", "slerp", "hold", "oracle", "lsopa-rt"
std::string_view TransitionMethodName(TransitionMethod method);
bool ParseTransitionMethod(std::string_view name, TransitionMethod* method);

// k such that every k-th frame of a motion at `frames_per_second` is one at `target_fps`;
// InputError naming `source` when the rate is not a whole multiple.
int ResampleStep(double frames_per_second, double target_fps, const std::string& source);

struct MotionTransitionOptions {
  TransitionMethod method = TransitionMethod::kLsopa;
  TransitionOptions transition;     // N, l, theta, RI's seed, the GPDM's iterations
  double frames_per_second = 30;
  int context = 45;                 // frames of A and of B the GPDM learns, at most
};

struct MotionInput {
  Skeleton skeleton;
  std::string asf_text;  // for the reference skeleton of the GPDM (A's)
  Motion motion;         // the frames to use (a range already cut)
  std::string source;    // for messages, e.g. "07_01.amc:100-400"
};

struct MotionTransitionResult {
  Motion motion;            // A, the transition, B, at frames_per_second, A's skeleton
  int first = 0;            // first transition frame in `motion`
  int frames = 0;           // N
  int context = 0;          // T, frames of A and of B the GPDM learnt (0 for SLERP)
  bool other_skeleton = false;  // B's skeleton was not A's
  double seconds = 0;       // generating the transition, GPDM training included
  // lsopa-rt: the largest change retraining made to a gait channel of LSOPA's transition,
  // and the mean distance its transition latent points moved, over |b - a|.
  double retrain_change_deg = 0;
  double retrain_latent_shift = 0;
};

// `truth`: the true transition's N frames at frames_per_second on A's skeleton, for the
// oracle only. InputError naming the motion for a rate that is not a multiple of
// frames_per_second, fewer than 3 frames after resampling, a channel of A that B lacks,
// non-finite values, bad options, or the oracle without the truth.
MotionTransitionResult TransitionBetween(const MotionInput& a, const MotionInput& b,
                                         const MotionTransitionOptions& options,
                                         const RowMatrixXd* truth = nullptr);

}  // namespace jgpm
