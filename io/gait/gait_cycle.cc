#include "io/gait/gait_cycle.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "io/base/error.h"

namespace jgpm {
namespace {

std::string Format(double value, int precision = 2) {
  std::ostringstream out;
  out.setf(std::ios::fixed);
  out.precision(precision);
  out << value;
  return out.str();
}

// Pose channels of frames [first, last] with `heading_deg` removed, unwrapped in time.
Eigen::MatrixXd PoseChannels(const GaitPoseLayout& layout, const Motion& motion, int first,
                             int last, double heading_deg) {
  Eigen::MatrixXd poses(last - first + 1, layout.NumChannels());
  Eigen::VectorXd pose(layout.NumChannels());
  for (int f = first; f <= last; ++f) {
    layout.FromFrame(motion.Frame(f), heading_deg, pose.data());
    poses.row(f - first) = pose.transpose();
  }
  for (int c = 0; c < poses.cols(); ++c) {
    Eigen::VectorXd column = poses.col(c);
    UnwrapDegrees(std::span<double>(column.data(), column.size()));
    poses.col(c) = column;
  }
  return poses;
}

// Pearson correlation of s[0, n-lag) with s[lag, n).
double Autocorrelation(const Eigen::VectorXd& s, int lag) {
  const int n = static_cast<int>(s.size()) - lag;
  const Eigen::VectorXd a = s.head(n).array() - s.head(n).mean();
  const Eigen::VectorXd b = s.segment(lag, n).array() - s.segment(lag, n).mean();
  const double denominator = a.norm() * b.norm();
  return denominator > 0 ? a.dot(b) / denominator : 0.0;
}

// A skeleton may lack the channel (GaitPoseLayout takes any dofs), so this is bad input.
int ChannelIndex(const GaitPoseLayout& layout, const std::string& name) {
  const auto& names = layout.channel_names();
  const auto it = std::find(names.begin(), names.end(), name);
  if (it == names.end()) {
    ThrowInputError(layout.source(), "the skeleton has no " + name + " dof, which finding gait cycles needs "
                                     "(the stride is read from lfemur.rx - rfemur.rx)");
  }
  return static_cast<int>(it - names.begin());
}

}  // namespace

bool GaitCycleOptions::Check(std::string* why) const {
  const char* problem = nullptr;
  if (poses_per_cycle < 2) problem = "poses_per_cycle must be at least 2";
  else if (!(min_cycle_s > 0 && max_cycle_s > min_cycle_s)) problem = "need 0 < min_cycle_s < max_cycle_s";
  else if (!(min_periodicity >= -1 && min_periodicity <= 1)) problem = "min_periodicity must be in [-1, 1]";
  else if (!(min_thigh_swing_deg >= 0)) problem = "min_thigh_swing_deg must be >= 0";
  else if (!(max_closure_deg > 0)) problem = "max_closure_deg must be > 0";
  if (problem && why) *why = problem;  // `why` may be null
  return problem == nullptr;
}

GaitCycle ExtractGaitCycle(const GaitPoseLayout& layout, const Motion& motion,
                           const GaitCycleOptions& options) {
  std::string why;
  JGPM_CHECK(options.Check(&why));
  GaitCycle cycle;
  const int left_thigh = ChannelIndex(layout, "lfemur.rx"), right_thigh = ChannelIndex(layout, "rfemur.rx");
  const int n = motion.NumFrames();
  const double fps = motion.frames_per_second;
  const int min_lag = std::max(2, static_cast<int>(std::lround(options.min_cycle_s * fps)));
  // A lag needs at least half a period of overlap to be measured.
  const int max_lag = std::min(static_cast<int>(std::lround(options.max_cycle_s * fps)),
                               (2 * n) / 3);
  if (max_lag <= min_lag + 1) {
    cycle.problem = "trial too short (" + std::to_string(n) + " frames) for a stride of at least " +
                    Format(options.min_cycle_s) + " s";
    return cycle;
  }

  const Eigen::MatrixXd all = PoseChannels(layout, motion, 0, n - 1, 0.0);
  const Eigen::VectorXd s = all.col(left_thigh) - all.col(right_thigh);
  cycle.thigh_swing_deg = s.maxCoeff() - s.minCoeff();
  if (cycle.thigh_swing_deg < options.min_thigh_swing_deg) {
    cycle.problem = "thighs barely swing (" + Format(cycle.thigh_swing_deg, 1) + " deg < " +
                    Format(options.min_thigh_swing_deg, 1) + "): not walking";
    return cycle;
  }

  // Period: the autocorrelation's highest interior maximum in [min_lag, max_lag].
  std::vector<double> r(max_lag + 2, -2.0);
  for (int lag = min_lag - 1; lag <= max_lag + 1 && lag < n - 1; ++lag) r[lag] = Autocorrelation(s, lag);
  int period = -1;
  for (int lag = min_lag; lag <= max_lag; ++lag) {
    if (r[lag] >= r[lag - 1] && r[lag] >= r[lag + 1] && (period < 0 || r[lag] > r[period])) {
      period = lag;
    }
  }
  if (period < 0) {
    cycle.problem = "no stride period between " + Format(options.min_cycle_s) + " and " +
                    Format(options.max_cycle_s) + " s";
    return cycle;
  }
  cycle.period_frames = period;
  cycle.periodicity = r[period];
  if (cycle.periodicity < options.min_periodicity) {
    cycle.problem = "not periodic (thigh autocorrelation " + Format(cycle.periodicity) + " < " +
                    Format(options.min_periodicity) + ")";
    return cycle;
  }

  // Cycle starts: maxima of s over +/- a quarter period.
  const int window = std::max(1, period / 4);
  std::vector<int> peaks;
  for (int t = window; t + window < n; ++t) {
    bool is_max = true;
    for (int k = t - window; k <= t + window && is_max; ++k) is_max = (k == t) || s[k] < s[t] || (s[k] == s[t] && k > t);
    if (is_max) peaks.push_back(t);
  }
  double best_closure = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i + 1 < peaks.size(); ++i) {
    const int length = peaks[i + 1] - peaks[i];
    if (std::abs(length - period) > 0.2 * period) continue;
    const double closure = std::sqrt(
        (all.row(peaks[i + 1]) - all.row(peaks[i])).squaredNorm() / static_cast<double>(all.cols()));
    if (closure < best_closure) {
      best_closure = closure;
      cycle.start_frame = peaks[i];
      cycle.end_frame = peaks[i + 1];
    }
  }
  if (!std::isfinite(best_closure)) {
    cycle.problem = "no two consecutive thigh maxima one period (" + std::to_string(period) +
                    " frames) apart";
    return cycle;
  }
  cycle.closure_deg = best_closure;

  // Heading: mean facing direction over the cycle.
  Eigen::Vector3d forward = Eigen::Vector3d::Zero();
  for (int f = cycle.start_frame; f < cycle.end_frame; ++f) {
    forward += layout.RootRotation(motion.Frame(f)).col(2);
  }
  cycle.heading_deg = std::atan2(forward.x(), forward.z()) * kRadToDeg;

  // Resample [start, end) to poses_per_cycle poses.
  const Eigen::MatrixXd span =
      PoseChannels(layout, motion, cycle.start_frame, cycle.end_frame, cycle.heading_deg);
  const int poses = options.poses_per_cycle;
  cycle.poses.resize(poses, layout.NumChannels());
  const double step = static_cast<double>(cycle.LengthFrames()) / poses;
  for (int k = 0; k < poses; ++k) {
    const double t = k * step;
    const int t0 = static_cast<int>(std::floor(t));
    const int t1 = std::min(t0 + 1, static_cast<int>(span.rows()) - 1);
    const double w = t - t0;
    cycle.poses.row(k) = (1.0 - w) * span.row(t0) + w * span.row(t1);
  }
  // Centre each channel's cycle mean in (-180, 180] (whole turns only).
  for (int c = 0; c < cycle.poses.cols(); ++c) {
    const double mean = cycle.poses.col(c).mean();
    cycle.poses.col(c).array() -= mean - WrapDegrees(mean);
  }
  cycle.start_frame += motion.first_frame_number;
  cycle.end_frame += motion.first_frame_number;

  if (cycle.closure_deg > options.max_closure_deg) {
    cycle.problem = "cycle does not close (first vs last pose " + Format(cycle.closure_deg) +
                    " deg RMS > " + Format(options.max_closure_deg) + ")";
    return cycle;
  }
  cycle.clean = true;
  return cycle;
}

}  // namespace jgpm
