// How far a track is from the truth, in the measures people compare trackers by (HumanEva,
// PARSEC bodytrack): the mean 3-D distance of corresponding joints in mm, absolute,
// root-relative (both roots at the origin) and Procrustes-aligned (the estimate rotated,
// translated and scaled onto the truth per frame, Umeyama's method), per joint, the rate
// of failed frames (mean absolute error above 150 mm) and of left-right leg swaps (the
// estimate fits better with its knees, ankles and feet exchanged side for side). Joints are matched by bone name: the
// estimate's skeleton (the model's) and the truth's (the subject's) both name CMU bones.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

namespace jgpm {

// Joint sets: bone names whose end points are compared.
// "bodytrack14": hips (l/rhipjoint), knees (l/rfemur), ankles (l/rtibia), shoulders
// (l/rclavicle), elbows (l/rhumerus), wrists (l/rradius), neck (thorax), head top (head),
// as the issue that set the peer's figures measured them.
const std::vector<std::string>& Bodytrack14();
// "gait17": the ends of the 17 measured gait joints (io/gait/gait_pose.h).
const std::vector<std::string>& Gait17();

struct TrackErrors {
  int frames = 0;              // frames compared (both present)
  double absolute_mm = 0;
  double root_relative_mm = 0;
  double procrustes_mm = 0;
  double failure_rate = 0;     // frames with absolute error > 150 mm
  double swap_rate = 0;        // frames whose legs fit better exchanged
  std::vector<std::string> joints;
  std::vector<double> per_joint_mm;     // absolute, per joint
  std::vector<double> per_frame_mm;     // absolute, per frame with truth (NaN: no estimate)
  Eigen::MatrixXd distances_mm;         // those frames x joints (NaN rows: no estimate)
};

// Frames are given as bone-end matrices (3 x bones, world mm) with their skeletons' bone
// names; an empty estimate matrix is a frame without an estimate (counted as failed).
// `root` names the root bone of both.
TrackErrors CompareTracks(const std::vector<Eigen::Matrix3Xd>& estimate, const std::vector<std::string>& estimate_bones,
                          const std::vector<Eigen::Matrix3Xd>& truth, const std::vector<std::string>& truth_bones,
                          const std::vector<std::string>& joints);

// The similarity transform (s R x + t) that best maps `from` onto `to` (3 x n each) in the
// least-squares sense, applied to `from` (Umeyama 1991).
Eigen::Matrix3Xd ProcrustesAlign(const Eigen::Matrix3Xd& from, const Eigen::Matrix3Xd& to);

}  // namespace jgpm
