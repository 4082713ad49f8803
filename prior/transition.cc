#include "prior/transition.h"

#include "io/asf.h"
#include "io/error.h"
#include "io/gait_pose.h"
#include "prior/training_set.h"

namespace jgpm {

Transition MakeTransition(const Eigen::MatrixXd& a_deg, const Eigen::MatrixXd& b_deg,
                          const ReferenceSkeleton& skeleton, const TransitionOptions& options) {
  std::string why;
  if (!options.path.Check(&why)) ThrowInputError("transition options", why);
  if (options.max_iterations < 1) ThrowInputError("transition options", "max_iterations must be >= 1");
  const GaitPoseLayout layout(ParseAsf(skeleton.asf, skeleton.trial + ".asf"), skeleton.trial + ".asf");
  if (a_deg.rows() < 3 || a_deg.rows() != b_deg.rows()) {
    ThrowInputError("transition", "motions A and B need the same number of frames, at least 3; got " +
                                      std::to_string(a_deg.rows()) + " and " + std::to_string(b_deg.rows()));
  }
  TrainingSet set = MakeSequenceSet({"A", "B"}, {a_deg, b_deg}, layout.channel_names(), layout.channel_joints());

  TrainingOptions training;
  training.kind = ModelKind::kGpdm;
  training.learning = Learning::kFull;
  training.threads = options.threads;
  training.full.max_iterations = options.max_iterations;
  Transition out;
  out.model = TrainGaitModel(std::move(set), "transition A -> B", skeleton, training);

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
  }
  out.poses_deg = out.model->MeanPoses(out.latent);
  return out;
}

}  // namespace jgpm
