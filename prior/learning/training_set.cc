#include "prior/learning/training_set.h"

#include "io/base/error.h"

namespace jgpm {

Eigen::MatrixXd ScaleGait(const Eigen::MatrixXd& cycle, double scale) {
  const Eigen::RowVectorXd mean = cycle.colwise().mean();
  return (scale * (cycle.rowwise() - mean)).rowwise() + mean;
}

TrainingSet MakeTrainingSet(const GaitDataset& dataset, const std::vector<double>& layer_scales) {
  if (layer_scales.empty()) ThrowInputError("--scales", "expected at least one layer scale");
  for (double s : layer_scales) {
    if (!(s > 0)) ThrowInputError("--scales", "layer scales must be > 0");
  }
  TrainingSet set;
  set.channel_names = dataset.channel_names;
  set.channel_joints = dataset.channel_joints;
  set.layer_scales = layer_scales;
  set.poses_per_gait = dataset.options.poses_per_cycle;
  std::vector<const GaitCycle*> cycles;
  for (const GaitTrial& trial : dataset.trials) {
    if (!trial.cycle.clean) continue;
    set.gait_ids.push_back(trial.id.name);
    cycles.push_back(&trial.cycle);
  }
  if (cycles.empty()) ThrowInputError("dataset " + dataset.split, "has no clean gait cycle to train on");
  const int poses = set.poses_per_gait;
  const int d = static_cast<int>(set.channel_names.size());
  const int n = set.NumLayers() * set.NumGaits() * poses;
  set.y_deg.resize(n, d);
  for (int layer = 0; layer < set.NumLayers(); ++layer) {
    for (int gait = 0; gait < set.NumGaits(); ++gait) {
      const Eigen::MatrixXd scaled = ScaleGait(cycles[gait]->poses, layer_scales[layer]);
      for (int pose = 0; pose < poses; ++pose) set.y_deg.row(set.Row(layer, gait, pose)) = scaled.row(pose);
    }
  }
  if (!set.y_deg.allFinite()) ThrowInputError("dataset " + dataset.split, "holds non-finite poses");
  Normalise(&set);
  return set;
}

TrainingSet MakeSequenceSet(const std::vector<std::string>& ids, const std::vector<Eigen::MatrixXd>& sequences,
                            const std::vector<std::string>& channel_names, const std::vector<int>& channel_joints) {
  if (sequences.empty() || sequences.size() != ids.size()) {
    ThrowInputError("motion sequences", "expected one id per sequence and at least one sequence");
  }
  TrainingSet set;
  set.channel_names = channel_names;
  set.channel_joints = channel_joints;
  set.layer_scales = {1.0};
  set.gait_ids = ids;
  set.poses_per_gait = static_cast<int>(sequences[0].rows());
  const int d = static_cast<int>(channel_names.size());
  if (set.poses_per_gait < 2) ThrowInputError("motion sequences", "need at least 2 poses each");
  set.y_deg.resize(static_cast<Eigen::Index>(sequences.size()) * set.poses_per_gait, d);
  for (size_t s = 0; s < sequences.size(); ++s) {
    if (sequences[s].rows() != set.poses_per_gait || sequences[s].cols() != d) {
      ThrowInputError("motion sequence " + ids[s], "has " + std::to_string(sequences[s].rows()) + " x " +
                                                       std::to_string(sequences[s].cols()) + " poses; expected " +
                                                       std::to_string(set.poses_per_gait) + " x " + std::to_string(d));
    }
    if (!sequences[s].allFinite()) ThrowInputError("motion sequence " + ids[s], "holds non-finite poses");
    set.y_deg.middleRows(static_cast<Eigen::Index>(s) * set.poses_per_gait, set.poses_per_gait) = sequences[s];
  }
  Normalise(&set);
  return set;
}

void Normalise(TrainingSet* set) {
  set->mean = set->y_deg.colwise().mean();
  const Eigen::MatrixXd centred = set->y_deg.rowwise() - set->mean;
  set->scale = (centred.colwise().squaredNorm() / set->y_deg.rows()).array().sqrt().max(1e-3).matrix();
  ComputeDerivedFields(set);
}

void ComputeDerivedFields(TrainingSet* set) {
  set->points.resize(set->y_deg.rows());
  for (int layer = 0; layer < set->NumLayers(); ++layer) {
    for (int gait = 0; gait < set->NumGaits(); ++gait) {
      for (int pose = 0; pose < set->poses_per_gait; ++pose) {
        set->points[set->Row(layer, gait, pose)] = {layer, gait, pose};
      }
    }
  }
  set->y = (set->y_deg.rowwise() - set->mean).array().rowwise() / set->scale.array();
}

}  // namespace jgpm
