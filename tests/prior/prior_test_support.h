// Small synthetic gait datasets for the prior tests: smooth periodic "walks" whose style
// varies with the gait, no CMU data needed.
#pragma once

#include <cmath>
#include <numbers>
#include <string>

#include "io/base/text_reader.h"
#include "io/gait/gait_dataset.h"
#include "io/mocap/asf.h"
#include "prior/model/train.h"
#include "test_support.h"

namespace jgpm::test {

// Channel `channel` of synthetic walk `gait` at `phase` (radians). Gaits and phases
// between the dataset's give walks a model of it was not built from.
inline double SyntheticWalkAngle(double gait, double phase, int channel) {
  return (10 + 3 * gait) * std::sin(phase + 0.4 * channel) + 5 * std::cos(2 * phase + gait) + channel;
}

inline GaitDataset SyntheticGaitDataset(int gaits, int poses, int channels) {
  GaitDataset dataset;
  dataset.split = "synthetic";
  dataset.options.poses_per_cycle = poses;
  for (int c = 0; c < channels; ++c) {
    dataset.channel_names.push_back("bone" + std::to_string(c) + ".rx");
    dataset.channel_joints.push_back(c);
  }
  for (int g = 0; g < gaits; ++g) {
    GaitTrial trial;
    trial.id.subject = "90";
    trial.id.name = "90_" + std::to_string(10 + g);
    trial.cycle.clean = true;
    trial.cycle.poses.resize(poses, channels);
    for (int p = 0; p < poses; ++p) {
      const double phase = 2 * std::numbers::pi * p / poses;
      for (int c = 0; c < channels; ++c) {
        trial.cycle.poses(p, c) = SyntheticWalkAngle(g, phase, c);
      }
    }
    dataset.trials.push_back(trial);
  }
  return dataset;
}

// The synthetic datasets use made-up channels, so models need a matching skeleton: the
// 43 gait channels of a real CMU skeleton (subject 35's), filled with synthetic walks.
inline ReferenceSkeleton Skeleton35() {
  return {"35_01", ReadTextFile(CmuRoot() / "subjects/35/35.asf", "asf")};
}

// Sparse learning of `kind` with `inducing` inputs, at most `iterations` L-BFGS iterations.
inline TrainingOptions SparseTraining(ModelKind kind, int inducing, int iterations) {
  TrainingOptions options;
  options.kind = kind;
  options.learning = Learning::kSparse;
  options.inducing = inducing;
  options.full.max_iterations = iterations;
  return options;
}

inline GaitDataset SyntheticWalks(int gaits, int poses) {
  const ReferenceSkeleton reference = Skeleton35();
  const GaitPoseLayout layout(ParseAsf(reference.asf, "35.asf"), "35.asf");
  GaitDataset dataset = SyntheticGaitDataset(gaits, poses, layout.NumChannels());
  dataset.channel_names = layout.channel_names();
  dataset.channel_joints = layout.channel_joints();
  return dataset;
}

// A model of `kind` briefly trained (`iterations` full-batch steps) on the first `trials`
// walks of the default training split: for tests that need a real prior's shape and
// ranges, not its quality.
inline std::unique_ptr<GaitModel> TrainOnFirstWalks(ModelKind kind, int trials, int iterations) {
  std::vector<TrialId> ids = SplitTrials("train");
  ids.resize(trials);
  const GaitDataset walks = PrepareGaitDataset(CmuRoot(), "first walks", ids, GaitCycleOptions{});
  TrainingOptions options;
  options.kind = kind;
  options.full.max_iterations = iterations;
  const GaitTrial& first = walks.trials[0];
  return TrainGaitModel(walks, {first.id.name, ReadTextFile(CmuRoot() / first.asf, "asf")}, options);
}

// A small model of `kind` on 5 synthetic walks of 10 poses.
inline std::unique_ptr<GaitModel> TrainOnSyntheticWalks(ModelKind kind, Learning learning = Learning::kFull) {
  TrainingOptions options;
  options.kind = kind;
  options.learning = learning;
  options.full.max_iterations = 300;
  options.local.max_steps = 3000;
  options.local.max_neighbourhood_fraction = 0.5;
  return TrainGaitModel(SyntheticWalks(5, 10), Skeleton35(), options);
}

// SyntheticWalks(gaits, poses) as walks of several people: gait g belongs to subject
// 91 + g % offsets.size() and holds itself offset by that subject's row of `offsets`
// (subjects x D degrees, added to every pose of its cycles).
inline GaitDataset SyntheticSubjectWalks(int gaits, int poses, const Eigen::MatrixXd& offsets) {
  GaitDataset dataset = SyntheticWalks(gaits, poses);
  for (int g = 0; g < gaits; ++g) {
    GaitTrial& trial = dataset.trials[g];
    const int s = g % static_cast<int>(offsets.rows());
    trial.id.subject = std::to_string(91 + s);
    trial.id.name = trial.id.subject + "_" + std::to_string(10 + g);
    trial.cycle.poses.rowwise() += offsets.row(s);
  }
  return dataset;
}

}  // namespace jgpm::test
