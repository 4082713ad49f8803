// One complete gait cycle (stride) from a walking trial, resampled to a fixed number of
// poses in the GaitPoseLayout representation.
//
// Method: the stride period is the lag that maximises the autocorrelation of the thigh
// signal s(t) = lfemur.rx - rfemur.rx (left minus right hip flexion), searched between
// min_cycle_s and max_cycle_s. Cycles start at maxima of s (right thigh furthest forward,
// close to the right heel strike), so every cycle starts at the same gait phase. Of the
// consecutive maxima pairs whose spacing is within 20% of the period, the one whose first
// and last poses differ least (the closure) is kept. The heading is the cycle's mean root
// facing direction. Channels are unwrapped along the trial before linear resampling, so
// angles crossing +/-180 degrees do not jump.
#pragma once

#include <string>

#include <Eigen/Core>

#include "io/gait/gait_pose.h"
#include "io/mocap/motion.h"

namespace jgpm {

struct GaitCycleOptions {
  // Poses the cycle is resampled to (the paper: 30).
  int poses_per_cycle = 30;
  // Range of stride periods searched, seconds (normal walking: about 0.9-1.3 s).
  double min_cycle_s = 0.7;
  double max_cycle_s = 1.7;
  // Lowest autocorrelation of the thigh signal at the period. Steady CMU walks reach
  // 0.93-1.0; dance and start/stop trials stay below 0.75.
  double min_periodicity = 0.85;
  // Smallest peak-to-peak swing of the thigh signal, degrees (walking: 40-80).
  double min_thigh_swing_deg = 20.0;
  // Largest RMS difference over channels between the cycle's first and last pose, degrees
  // (steady CMU walks: 1-4.5).
  double max_closure_deg = 6.0;

  bool Check(std::string* why) const;
};

struct GaitCycle {
  bool clean = false;     // a cycle meeting the options was found
  std::string problem;    // why not, when !clean
  // AMC frame numbers: the cycle covers frames [start_frame, end_frame); end_frame is the
  // first frame of the next cycle.
  int start_frame = 0;
  int end_frame = 0;
  double period_frames = 0;   // from the autocorrelation
  double periodicity = 0;     // autocorrelation at that period
  double thigh_swing_deg = 0;
  double closure_deg = 0;     // RMS first-vs-last pose difference, degrees
  double heading_deg = 0;     // removed from the root rotation
  // poses_per_cycle x layout channels, degrees; pose k is at phase k / poses_per_cycle.
  Eigen::MatrixXd poses;

  int LengthFrames() const { return end_frame - start_frame; }
};

// Never throws for motion that is not a clean walk: `clean` and `problem` say so.
// InputError naming the skeleton when it has no lfemur.rx or rfemur.rx dof.
GaitCycle ExtractGaitCycle(const GaitPoseLayout& layout, const Motion& motion,
                           const GaitCycleOptions& options = {});

}  // namespace jgpm
