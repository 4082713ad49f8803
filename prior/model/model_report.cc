#include "prior/model/model_report.h"

#include <cmath>
#include <cstdio>

namespace jgpm {

double TrainingReconstructionErrorMm(const GaitModel& model) {
  const TrainingSet& set = model.data().set;
  double total = 0;
  Eigen::VectorXd pose;
  Eigen::Matrix3Xd estimated, truth;
  for (int i = 0; i < model.NumPoints(); ++i) {
    model.Predict(model.latent().row(i).transpose(), &pose, nullptr);
    model.JointPositions(pose, &estimated);
    model.JointPositions(set.y_deg.row(i).transpose(), &truth);
    total += (estimated - truth).colwise().norm().mean();
  }
  return total / model.NumPoints();
}

std::string DescribeModel(const GaitModel& model) {
  const GaitModelData& d = model.data();
  const TrainingSet& set = d.set;
  char line[512];
  std::string out;
  std::snprintf(line, sizeof(line), "%s model: %d latent points (%d gaits x %d poses x %d layer(s)), %d channels, split %s\n",
                std::string(ModelKindName(d.kind)).c_str(), model.NumPoints(), set.NumGaits(),
                set.poses_per_gait, set.NumLayers(), model.NumChannels(), d.split.c_str());
  out += line;
  if (d.params.log_beta.size() == 3) {
    const Eigen::Vector3d b = d.params.log_beta.array().exp();
    std::snprintf(line, sizeof(line), "mapping kernel: b1 %.4g, b2 %.4g (fixed), noise std %.4g\n", b[0], b[1], 1 / std::sqrt(b[2]));
    out += line;
  }
  if (d.params.log_alpha.size() == 4) {
    const Eigen::Vector4d a = d.params.log_alpha.array().exp();
    std::snprintf(line, sizeof(line), "dynamics kernel: a1 %.4g, a2 %.4g, a3 %.4g, noise std %.4g (fixed)\n", a[0], a[1], a[2], 1 / std::sqrt(a[3]));
    out += line;
  }
  const Eigen::RowVector3d low = model.latent().colwise().minCoeff(), high = model.latent().colwise().maxCoeff();
  std::snprintf(line, sizeof(line), "latent extent: x %.2f..%.2f, y %.2f..%.2f, z %.2f..%.2f\n", low[0], high[0], low[1], high[1], low[2], high[2]);
  out += line;
  out += d.summary.BriefReport() + "\n";
  std::snprintf(line, sizeof(line), "training reconstruction error: %.2f mm (mean over 17 joints, skeleton of %s)\n",
                TrainingReconstructionErrorMm(model), d.skeleton_trial.c_str());
  out += line;
  return out;
}

}  // namespace jgpm
