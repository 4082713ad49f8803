#include "prior/motion/motion_transition.h"

#include <chrono>
#include <cmath>
#include <span>

#include "io/base/enum_name.h"
#include "io/base/error.h"
#include "io/base/text_reader.h"
#include "io/gait/gait_pose.h"
#include "io/mocap/rotation.h"
#include "prior/motion/slerp_transition.h"

namespace jgpm {
namespace {

// Every k-th frame, k = rate / fps; A's selection ends on its last frame, B's starts on
// its first.
RowMatrixXd Resample(const MotionInput& in, double fps, bool end_aligned) {
  const int k = ResampleStep(in.motion.frames_per_second, fps, in.source);
  const int n = in.motion.NumFrames(), count = (n + k - 1) / k;
  if (count < 3) {
    ThrowInputError(in.source, "has " + std::to_string(n) + " frames, " + std::to_string(count) + " at " +
                                   FormatShortest(fps) + " frames/s; a transition needs at least 3");
  }
  if (!in.motion.values.allFinite()) ThrowInputError(in.source, "holds a non-finite value");
  RowMatrixXd out(count, in.motion.values.cols());
  const int offset = end_aligned ? (n - 1) - (count - 1) * k : 0;
  for (int i = 0; i < count; ++i) out.row(i) = in.motion.values.row(offset + i * k);
  return out;
}

// B's frames on A's skeleton: each of A's channels from B's channel of the same name.
RowMatrixXd OnSkeleton(const RowMatrixXd& frames, const Skeleton& from, const Skeleton& to, const std::string& source) {
  const std::vector<std::string> from_names = from.ChannelNames(), to_names = to.ChannelNames();
  if (from_names == to_names) return frames;
  RowMatrixXd out(frames.rows(), static_cast<Eigen::Index>(to_names.size()));
  for (size_t c = 0; c < to_names.size(); ++c) {
    const auto it = std::find(from_names.begin(), from_names.end(), to_names[c]);
    if (it == from_names.end()) {
      ThrowInputError(source, "its skeleton has no channel " + to_names[c] + ", which motion A's has");
    }
    out.col(static_cast<Eigen::Index>(c)) = frames.col(it - from_names.begin());
  }
  return out;
}

}  // namespace

std::string_view TransitionMethodName(TransitionMethod method) {
  switch (method) {
    case TransitionMethod::kLsopa: return "lsopa";
    case TransitionMethod::kLinear: return "li";
    case TransitionMethod::kRandom: return "ri";
    case TransitionMethod::kSlerp: return "slerp";
    case TransitionMethod::kHold: return "hold";
    case TransitionMethod::kOracle: return "oracle";
    case TransitionMethod::kLsopaRetrained: return "lsopa-rt";
  }
  return "?";
}

bool ParseTransitionMethod(std::string_view name, TransitionMethod* method) {
  return ParseByName(name,
                     {TransitionMethod::kLsopa, TransitionMethod::kLinear, TransitionMethod::kRandom,
                      TransitionMethod::kSlerp, TransitionMethod::kHold, TransitionMethod::kOracle,
                      TransitionMethod::kLsopaRetrained},
                     TransitionMethodName, method);
}

int ResampleStep(double frames_per_second, double target_fps, const std::string& source) {
  const double ratio = frames_per_second / target_fps;
  const int k = static_cast<int>(std::lround(ratio));
  if (k < 1 || std::abs(ratio - k) > 1e-6) {
    ThrowInputError(source, "is at " + FormatShortest(frames_per_second) + " frames/s, not a whole multiple of " +
                                FormatShortest(target_fps));
  }
  return k;
}

MotionTransitionResult TransitionBetween(const MotionInput& a, const MotionInput& b,
                                         const MotionTransitionOptions& options, const RowMatrixXd* truth) {
  std::string why;
  if (!options.transition.path.Check(&why)) ThrowInputError("transition options", why);
  if (!(options.frames_per_second > 0) || options.context < 3) {
    ThrowInputError("transition options", "frames_per_second must be > 0 and context >= 3");
  }
  const auto start = std::chrono::steady_clock::now();
  const RowMatrixXd frames_a = Resample(a, options.frames_per_second, true);
  const RowMatrixXd frames_b =
      OnSkeleton(Resample(b, options.frames_per_second, false), b.skeleton, a.skeleton, b.source);
  const int n = options.transition.path.frames;
  const Eigen::RowVectorXd last_a = frames_a.row(frames_a.rows() - 1), first_b = frames_b.row(0);

  MotionTransitionResult result;
  result.frames = n;
  result.first = static_cast<int>(frames_a.rows());
  result.other_skeleton = a.asf_text != b.asf_text;
  if (options.method == TransitionMethod::kOracle &&
      (!truth || truth->rows() != n || truth->cols() != frames_a.cols() || !truth->allFinite())) {
    ThrowInputError("--method oracle", "needs the true transition (" + std::to_string(n) +
                                           " finite frames on A's skeleton): only the evaluation suite has it");
  }
  RowMatrixXd transition(n, frames_a.cols());
  if (options.method == TransitionMethod::kSlerp) {
    transition = SlerpTransition(a.skeleton, last_a, first_b, n);
  } else if (options.method == TransitionMethod::kHold) {
    transition = last_a.replicate(n, 1);
  } else {
    const GaitPoseLayout layout(a.skeleton, a.source);
    const int t = static_cast<int>(std::min<Eigen::Index>({frames_a.rows(), frames_b.rows(), options.context}));
    result.context = t;
    // Headings: A's last frame's is taken out of A, B's first frame's out of B, so that both
    // are seen facing +z (a turn between them would otherwise put B's root angles on
    // another Euler branch, and the path would tumble the body); the transition turns
    // from one to the other evenly, as the root travels.
    const double heading_a = HeadingOf(layout.RootRotation(last_a.data()));
    const double turn = WrapDegrees(HeadingOf(layout.RootRotation(first_b.data())) - heading_a);
    // A's last t and B's first t frames as gait poses, unwrapped along A then B.
    Eigen::MatrixXd poses(2 * t, layout.NumChannels());
    for (int i = 0; i < 2 * t; ++i) {
      const Eigen::RowVectorXd frame = i < t ? frames_a.row(frames_a.rows() - t + i) : frames_b.row(i - t);
      Eigen::RowVectorXd pose(layout.NumChannels());
      layout.FromFrame(frame.data(), i < t ? heading_a : heading_a + turn, pose.data());
      poses.row(i) = pose;
    }
    for (Eigen::Index c = 0; c < poses.cols(); ++c) {
      Eigen::VectorXd column = poses.col(c);
      UnwrapDegrees(std::span<double>(column.data(), column.size()));
      poses.col(c) = column;
    }
    // The frame of transition frame i turns by s_i of the turn, s_i = (i + 1) / (N + 1).
    const auto heading_at = [&](int i) { return heading_a + turn * (i + 1) / (n + 1); };
    TransitionOptions transition_options = options.transition;
    transition_options.method = options.method == TransitionMethod::kLinear   ? LatentPathMethod::kLinear
                                : options.method == TransitionMethod::kRandom ? LatentPathMethod::kRandom
                                : options.method == TransitionMethod::kOracle ? LatentPathMethod::kOracle
                                                                              : LatentPathMethod::kLsopa;
    transition_options.retrain = options.method == TransitionMethod::kLsopaRetrained;
    Eigen::MatrixXd truth_poses;
    if (truth) {
      // The truth as the model would have to produce it: with the headings the output uses,
      // each channel on the unwrapped motions' branch (within 180 degrees of A's end).
      truth_poses.resize(n, layout.NumChannels());
      Eigen::RowVectorXd pose(layout.NumChannels());
      for (int i = 0; i < n; ++i) {
        layout.FromFrame(truth->row(i).data(), heading_at(i), pose.data());
        for (Eigen::Index c = 0; c < pose.size(); ++c) {
          truth_poses(i, c) = poses(t - 1, c) + WrapDegrees(pose(c) - poses(t - 1, c));
        }
      }
    }
    const Transition generated = MakeTransition(poses.topRows(t), poses.bottomRows(t), {a.source, a.asf_text},
                                                transition_options, truth ? &truth_poses : nullptr);
    Eigen::MatrixXd generated_poses = generated.poses_deg;
    if (generated.retrained) {
      generated_poses = generated.retrained_poses_deg;
      result.retrain_change_deg = (generated_poses - generated.poses_deg).cwiseAbs().maxCoeff();
      const Eigen::MatrixXd& x = generated.model->latent();
      const double span = (x.row(t) - x.row(t - 1)).norm();
      result.retrain_latent_shift =
          (generated.retrained_latent - generated.latent).rowwise().norm().mean() / std::max(span, 1e-12);
    }
    Eigen::RowVectorXd frame(frames_a.cols());
    for (int i = 0; i < n; ++i) {
      // What the model does not carry, linearly; then the generated gait channels.
      const double s = static_cast<double>(i + 1) / (n + 1);
      transition.row(i) = (1 - s) * last_a + s * first_b;
      const Eigen::RowVectorXd pose = generated_poses.row(i);
      layout.ToFrame(pose.data(), heading_at(i), Eigen::Vector3d::Zero(), frame.data());
      for (int c : layout.skeleton_channels()) transition(i, c) = frame(c);
    }
  }
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  result.motion.frames_per_second = options.frames_per_second;
  result.motion.values.resize(frames_a.rows() + n + frames_b.rows(), frames_a.cols());
  result.motion.values << frames_a, transition, frames_b;
  return result;
}

}  // namespace jgpm
