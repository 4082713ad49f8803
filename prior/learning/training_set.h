// The training data of a gait model: gait cycles from a prepared dataset, optionally
// diversified into layers of scaled gaits (ML-JGPM, METHOD.md section 2), normalised per
// channel.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "io/gait/gait_dataset.h"

namespace jgpm {

// Where a training point comes from. Rows are ordered layer, then gait, then pose:
// row = (layer * num_gaits + gait) * poses_per_gait + pose.
struct TrainingPoint {
  int layer = 0;
  int gait = 0;  // index into TrainingSet::gait_ids
  int pose = 0;  // 0 .. poses_per_gait - 1 along the cycle
};

struct TrainingSet {
  std::vector<std::string> channel_names;
  std::vector<int> channel_joints;        // GaitJoints() index of each channel
  std::vector<std::string> gait_ids;      // trial ids, dataset order
  std::vector<double> layer_scales;       // e.g. {0.4, 1, 1.25}; {1} for one layer
  int poses_per_gait = 0;
  std::vector<TrainingPoint> points;
  Eigen::MatrixXd y_deg;                  // N x D poses, degrees
  // Normalisation: y = (y_deg - mean) / scale, per channel. Scale is the channel's standard
  // deviation over the training set, floored at 1e-3 degrees so near-constant channels
  // cannot blow the model up (METHOD.md section 6).
  Eigen::RowVectorXd mean;
  Eigen::RowVectorXd scale;
  Eigen::MatrixXd y;

  int NumPoints() const { return static_cast<int>(points.size()); }
  int NumChannels() const { return static_cast<int>(y.cols()); }
  int NumGaits() const { return static_cast<int>(gait_ids.size()); }
  int NumLayers() const { return static_cast<int>(layer_scales.size()); }
  int Row(int layer, int gait, int pose) const {
    return (layer * NumGaits() + gait) * poses_per_gait + pose;
  }
};

// Scales one gait cycle's channels about their cycle means (paper eq. 5):
//   y'_{u,k} = mean_u(y_{.,k}) + s (y_{u,k} - mean_u(y_{.,k})).
Eigen::MatrixXd ScaleGait(const Eigen::MatrixXd& cycle, double scale);

// A training set of motion sequences of equal length (one "gait" each, one layer), such
// as the two motions a transition joins. InputError for unequal or non-finite sequences.
TrainingSet MakeSequenceSet(const std::vector<std::string>& ids, const std::vector<Eigen::MatrixXd>& sequences,
                            const std::vector<std::string>& channel_names, const std::vector<int>& channel_joints);

// Sets mean and scale from y_deg (each channel's mean and standard deviation, floored as
// above), then the derived fields.
void Normalise(TrainingSet* set);

// Fills `points` and `y` from the counts, y_deg, mean and scale (what a model file stores).
void ComputeDerivedFields(TrainingSet* set);

// Builds the training set from the clean cycles of `dataset`, one layer per scale.
// InputError if the dataset has no clean cycle or the scales are not positive.
TrainingSet MakeTrainingSet(const GaitDataset& dataset, const std::vector<double>& layer_scales);

}  // namespace jgpm
