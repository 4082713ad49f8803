#include "prior/motion/transition.h"

#include "io/base/error.h"
#include "io/gait/gait_pose.h"
#include "io/mocap/asf.h"
#include "prior/learning/training_set.h"
#include "prior/model/inference.h"

namespace jgpm {
namespace {

TrainingOptions GpdmTraining(const TransitionOptions& options) {
  TrainingOptions training;
  training.kind = ModelKind::kGpdm;
  training.learning = Learning::kFull;
  training.threads = options.threads;
  training.full.max_iterations = options.max_iterations;
  return training;
}

// Per true frame, the latent point whose mean pose fits it best: eq. 15 without the
// dynamics term (a tolerance of 1e6 mean steps leaves the frames independent).
Eigen::MatrixXd OraclePath(const GaitModel& model, const Eigen::MatrixXd& truth_deg) {
  PoseObservations observations;
  observations.poses_deg = truth_deg;
  InferenceOptions fit;
  fit.dynamics_tolerance = 1e6;
  fit.max_iterations = 50;
  return InferLatentSequence(model, observations, fit).latent;
}

}  // namespace

Transition MakeTransition(const Eigen::MatrixXd& a_deg, const Eigen::MatrixXd& b_deg,
                          const ReferenceSkeleton& skeleton, const TransitionOptions& options,
                          const Eigen::MatrixXd* truth_deg) {
  std::string why;
  if (!options.path.Check(&why)) ThrowInputError("transition options", why);
  if (options.max_iterations < 1) ThrowInputError("transition options", "max_iterations must be >= 1");
  const GaitPoseLayout layout(ParseAsf(skeleton.asf, skeleton.trial + ".asf"), skeleton.trial + ".asf");
  if (a_deg.rows() < 3 || a_deg.rows() != b_deg.rows()) {
    ThrowInputError("transition", "motions A and B need the same number of frames, at least 3; got " +
                                      std::to_string(a_deg.rows()) + " and " + std::to_string(b_deg.rows()));
  }
  if (options.method == LatentPathMethod::kOracle &&
      (!truth_deg || truth_deg->rows() != options.path.frames || truth_deg->cols() != a_deg.cols())) {
    ThrowInputError("transition", "the latent oracle needs the true transition, " +
                                      std::to_string(options.path.frames) + " poses of the motions' channels");
  }
  TrainingSet set = MakeSequenceSet({"A", "B"}, {a_deg, b_deg}, layout.channel_names(), layout.channel_joints());

  Transition out;
  out.model = TrainGaitModel(std::move(set), "transition A -> B", skeleton, GpdmTraining(options));

  const Eigen::MatrixXd& x = out.model->latent();
  const Eigen::Index t = a_deg.rows();
  const Eigen::Vector3d a = x.row(t - 1).transpose(), b = x.row(t).transpose();
  const MeanPoseFunction mean_poses = [&](const Eigen::MatrixXd& xs) { return out.model->MeanPoses(xs); };
  switch (options.method) {
    case LatentPathMethod::kLsopa: {
      const Eigen::Vector3d c = ReferenceDirection(x.row(t - 2).transpose(), a, b, x.row(t + 1).transpose());
      out.latent = LsopaPath(a, b, c, options.path, mean_poses);
      break;
    }
    case LatentPathMethod::kLinear:
      out.latent = LinearPath(a, b, options.path.frames);
      break;
    case LatentPathMethod::kRandom:
      out.latent = RandomPath(a, b, options.path.frames, options.seed);
      break;
    case LatentPathMethod::kOracle:
      out.latent = OraclePath(*out.model, *truth_deg);
      break;
  }
  out.poses_deg = out.model->MeanPoses(out.latent);

  if (options.retrain) {
    // Algorithm 1: [A; transition; B] as one sequence, from where the first model ended.
    const int n = options.path.frames;
    Eigen::MatrixXd joined(2 * t + n, a_deg.cols());
    joined << a_deg, out.poses_deg, b_deg;
    TrainingOptions training = GpdmTraining(options);
    GpParameters start = out.model->data().params;
    start.x.resize(2 * t + n, 3);
    start.x << x.topRows(t), out.latent, x.bottomRows(t);
    training.start = std::move(start);
    out.retrained = TrainGaitModel(
        MakeSequenceSet({"A;transition;B"}, {joined}, layout.channel_names(), layout.channel_joints()),
        "transition A -> B, retrained", skeleton, training);
    out.retrained_latent = out.retrained->latent().middleRows(t, n);
    out.retrained_poses_deg = out.retrained->MeanPoses(out.retrained_latent);
  }
  return out;
}

}  // namespace jgpm
