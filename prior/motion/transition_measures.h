// How close a generated transition is to the true one (issue #16), on forward kinematics
// of the trial's own skeleton. Both motions hold the same frames around the transition
// (motion A, the N transition frames at [first, first + N), motion B); only the transition
// frames differ. The measures:
//   eq23          per frame, the mean 3-D distance (mm) of the 17 measured joints (the
//                 LSOPA paper's eq. 23), in the world and root-aligned (each frame's root
//                 subtracted from both), and their means over the transition;
//   L2P           mean over frames of the L2 norm of the measured joints' global positions'
//                 difference (metres; Harvey et al. 2020 normalise by their data's spread,
//                 so compare as ratios to SLERP, not to their numbers);
//   L2Q           mean over frames of the L2 norm of the difference of every bone's global
//                 rotation as a unit quaternion, each taken in the truth's hemisphere;
//   NPSS          normalised power spectrum similarity (Gopalakrishnan et al. 2019): per
//                 quaternion component over the transition, the earth mover's distance
//                 between the two normalised power spectra, weighted by the truth's power;
//   foot skating  mean horizontal speed (m/s) of the feet while within contact_mm of the
//                 floor, over the transition (the truth's own beside it);
//   seam jumps    at each seam, the mean over the measured joints of the change of
//                 velocity across it, |p[s+1] - 2 p[s] + p[s-1]| x fps (m/s), s being A's
//                 last frame and the transition's last frame (the truth's own beside it).
#pragma once

#include <array>
#include <vector>

#include <Eigen/Core>

#include "io/mocap/motion.h"
#include "io/mocap/skeleton.h"

namespace jgpm {

struct TransitionWindow {
  int first = 0;    // first transition frame (>= 2: A's last two frames come before)
  int frames = 0;   // N (>= 1); B's first two frames follow
  double frames_per_second = 30;
  double floor_mm = 0;       // floor height (y), e.g. the truth's lowest foot point
  double contact_mm = 25;    // a foot this near the floor is on it
};

struct TransitionMeasures {
  std::vector<double> eq23_mm;               // per transition frame
  std::vector<double> eq23_root_aligned_mm;
  double eq23_mean_mm = 0;
  double eq23_root_aligned_mean_mm = 0;
  double l2p_m = 0;
  double l2q = 0;
  double npss = 0;
  double foot_skate_mps = 0, true_foot_skate_mps = 0;  // 0 when no foot touched the floor
  std::array<double, 2> seam_jump_mps{}, true_seam_jump_mps{};
};

// `truth` and `estimate`: skeleton frames (rows of NumChannels() values) of the same
// length. InputError for sizes or a window that do not fit, non-finite values, or a
// skeleton without the gait joints or feet.
TransitionMeasures MeasureTransition(const Skeleton& skeleton, const RowMatrixXd& truth, const RowMatrixXd& estimate,
                                     const TransitionWindow& window);

}  // namespace jgpm
