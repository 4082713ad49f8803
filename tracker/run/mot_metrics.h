// How well several people are followed, in the CLEAR MOT measures (Bernardin and
// Stiefelhagen, "Evaluating multiple object tracking performance", 2008) that multi-person
// trackers report, on floor positions: a tracked person is matched to a true one when its
// root is within `match_mm` of the true root on the floor (500 mm: the rule, about
// a person's width, so that two people side by side are not confused).
// Per frame, correspondences of the frame before are kept while still within the
// threshold; the rest are paired at least total distance (tracker/filter/assignment.h). A
// true person paired with another tracked id than the last one it had is an identity
// switch; a true person not paired is a miss; a tracked one not paired a false positive.
//   MOTA = 1 - (misses + false positives + switches) / true person-frames
//   MOTP = mean floor distance of the pairs, mm (the paper's distance form; boxes report
//          overlap instead)
// A fragmentation is a true track's run of unpaired frames between two paired ones.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "tracker/clip/clip_format.h"

namespace jgpm {

struct MotPoint {
  int id = 0;
  Eigen::Vector2d floor_mm = Eigen::Vector2d::Zero();  // the root's (x, z)
};

struct MotFrame {
  std::vector<MotPoint> truth, tracked;  // ids unique within each list
};

struct MotPair {
  int frame = 0, truth_id = 0, tracked_id = 0;
  double distance_mm = 0;
};

struct MotResult {
  int frames = 0;
  int truth = 0;           // true person-frames
  int truth_tracks = 0;    // distinct true ids
  int pairs = 0, misses = 0, false_positives = 0, id_switches = 0, fragmentations = 0;
  double mota = 0;         // with nobody to find: 1, or minus the false positives
  double motp_mm = 0;      // 0 without pairs
  std::vector<MotPair> paired;
};

// std::invalid_argument for an id given twice in one frame's list or a non-finite point.
MotResult ClearMot(const std::vector<MotFrame>& frames, double match_mm = 500);

// At least half of the joints inside some camera's image.
bool JointsHalfInView(const std::vector<Camera>& cameras, const Eigen::Matrix3Xd& joints_mm);

// The true people of a clip per frame (up to `frames`): every walker in the scene whose
// joints are at least half inside some camera's image (the cameras that rendered the
// images); a person hidden behind another still counts, as someone to keep. One-walker
// clips: the walker as id 1.
std::vector<std::vector<MotPoint>> TruePeople(const ClipGroundTruth& truth, int frames);

}  // namespace jgpm
