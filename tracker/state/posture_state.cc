#include "tracker/state/posture_state.h"

#include <algorithm>

#include <Eigen/Cholesky>

#include "io/base/error.h"

namespace jgpm {

bool PostureStateOptions::Check(std::string* why) const {
  const char* problem = nullptr;
  if (frames < 1) problem = "posture frames must be >= 1";
  else if (!(frame_deg > 0)) problem = "posture frame_deg must be > 0";
  if (problem && why) *why = problem;  // `why` may be null
  return problem == nullptr;
}

PostureState::PostureState(PosturePrior prior, const PostureStateOptions& options)
    : prior_(std::move(prior)), options_(options) {
  std::string why;
  if (!options.Check(&why)) ThrowInputError("posture state options", why);
  prior_precision_ = prior_.whitening().transpose() * prior_.whitening();
  Reset();
}

void PostureState::Reset() {
  sum_ = offset_ = Eigen::VectorXd::Zero(prior_.NumChannels());
  count_ = 0;
}

void PostureState::Add(const Eigen::VectorXd& deviation_deg) {
  JGPM_CHECK(deviation_deg.size() == prior_.NumChannels());
  const double n = options_.frames;
  if (count_ >= n) sum_ *= 1 - 1 / n;  // from now on a window of n frames
  sum_ += deviation_deg;
  count_ = std::min(count_ + 1, n);
  const double precision = 1 / (options_.frame_deg * options_.frame_deg);
  Eigen::MatrixXd normal = prior_precision_;
  normal.diagonal().array() += count_ * precision;
  offset_ = normal.llt().solve(precision * sum_);  // SPD: Sigma^-1 plus a positive diagonal
}

}  // namespace jgpm
