// The tracked person's posture (issue #15): an offset delta per gait channel from the
// prior's mean poses, a per-person state under the training subjects' posture prior
// N(0, Sigma) (prior/model/posture_prior.h). The tracker's joint-angle refinement
// (tracker/filter/pose_refiner.h) gives each frame a deviation d_t = refined pose - model pose, a
// noisy view of delta (noise frame_deg per channel); delta is the posterior mean
//   delta = (Sigma^-1 + n / r^2 I)^-1 sum_t d_t / r^2,
// over the first `frames` frames, then over an exponentially decaying window of that
// length: estimated at the start, then updated slowly. Where the silhouettes cannot show a
// channel (the head's roll seen from the side), the deviations stay where the search
// started, and the prior pulls delta back toward zero; the prior's correlations carry what
// is seen to channels that move with it in the training subjects.
#pragma once

#include <string>

#include <Eigen/Core>

#include "prior/model/posture_prior.h"

namespace jgpm {

struct PostureStateOptions {
  int frames = 30;         // frames delta is estimated over, then its memory
  double frame_deg = 8.0;  // r: how far one frame's deviation strays from delta

  bool Check(std::string* why) const;
};

class PostureState {
 public:
  // InputError for bad options.
  PostureState(PosturePrior prior, const PostureStateOptions& options);

  // Forgets the person: delta = 0 (a new start).
  void Reset();
  // Takes in one frame's deviation (degrees, every channel).
  void Add(const Eigen::VectorXd& deviation_deg);
  const Eigen::VectorXd& offset() const { return offset_; }  // delta, degrees
  double frames() const { return count_; }                    // n, at most options.frames

 private:
  PosturePrior prior_;
  PostureStateOptions options_;
  Eigen::MatrixXd prior_precision_;  // Sigma^-1 = W^T W
  Eigen::VectorXd sum_, offset_;
  double count_ = 0;
};

}  // namespace jgpm
