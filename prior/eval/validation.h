// Model validation as the paper does it (section VI-C; METHOD.md section 4): how well a
// gait model represents gait cycles it was not trained on. Each test cycle is scaled about
// its mean (eq. 5), then given to sequence inference (prior/model/inference.h) whole
// (interpolation), with joints missing (reconstruction) or with white Gaussian noise
// (filtering); the error is the mean 3-D position error of the 17 measured joints, in mm,
// between the model's poses and the clean scaled cycle, both on the test subject's own
// skeleton.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "io/gait/gait_dataset.h"
#include "io/gait/gait_pose.h"
#include "prior/model/gait_model.h"
#include "prior/model/inference.h"

namespace jgpm {

enum class ValidationTask { kInterpolation, kReconstruction, kFiltering };
enum class MissingPart { kNone, kLeftArm, kLeftLeg, kLeftSide };

std::string_view ValidationTaskName(ValidationTask task);  // "interpolation", ...
bool ParseValidationTask(std::string_view name, ValidationTask* task);
std::string_view MissingPartName(MissingPart part);  // "none", "left-arm", "left-leg", "left-side"
bool ParseMissingPart(std::string_view name, MissingPart* part);
// GaitJoints() names of the joints a part leaves out (left arm: humerus, radius, wrist).
std::vector<std::string_view> MissingJoints(MissingPart part);

struct ValidationCase {
  ValidationTask task = ValidationTask::kInterpolation;
  double scale = 1.0;                        // stride scale applied to each test cycle
  MissingPart missing = MissingPart::kNone;  // reconstruction: the joints not observed
  double noise = 0;                          // filtering: noise std / each channel's std over the cycle
  int draws = 5;                             // filtering: noise draws (seeds 1..draws)

  bool Check(std::string* why) const;
  // e.g. "interpolation s=0.5", "reconstruction left-arm s=1", "filtering 10% s=1".
  std::string Label() const;
};

// One test cycle and the kinematics of its subject's skeleton.
struct ValidationTrial {
  std::string id;
  Eigen::MatrixXd poses_deg;  // T x D
  std::shared_ptr<const GaitPoseKinematics> kinematics;
};

// The clean cycles of a prepared dataset with their skeletons, read from its data root.
// InputError if a skeleton cannot be read or has other channels than `model`, or if no
// trial has a clean cycle.
std::vector<ValidationTrial> LoadValidationTrials(const GaitDataset& dataset, const GaitModel& model);

struct ValidationResult {
  ValidationCase validation_case;
  std::vector<std::string> trials;
  std::vector<double> trial_errors_mm;  // per trial (filtering: mean over the draws)
  // Where the error comes from, over every trial (and draw): each of the 17 measured
  // joints' mean distance (their mean is mean_error_mm), each channel's mean absolute
  // angle error.
  std::vector<std::string> joint_names, channel_names;
  std::vector<double> joint_errors_mm, channel_errors_deg;
  // With inference's adapt_posture, each channel's posture offset, mean over every trial
  // and draw: what the test subjects' posture differs by, as the prior allows it.
  std::vector<double> channel_posture_deg;
  std::vector<double> channel_gain;  // and each channel's amplitude gain, likewise
  std::vector<double> draw_errors_mm;   // filtering: mean over the trials, per draw
  double mean_error_mm = 0;
  double std_error_mm = 0;              // filtering: over the draws; else over the trials
  // Inferences (trials x draws) that ended in a numerical failure: their errors are those
  // of the last latent points Levenberg-Marquardt could evaluate.
  int inference_failures = 0;
  double seconds = 0;
};

// Runs one case on every trial, on `threads` threads (the result does not depend on it).
// The OpenBLAS thread count is one while the trials run, and restored after. InputError
// when a trial's inference gives non-finite poses; any other exception of a worker is
// rethrown here.
ValidationResult Validate(const GaitModel& model, const std::vector<ValidationTrial>& trials,
                          const ValidationCase& validation_case, const InferenceOptions& inference = {},
                          int threads = 1);

// A model's results on several cases.
struct ModelResults {
  std::string model;  // a name for tables and legends, e.g. the file's stem
  std::vector<ValidationResult> results;
};

// Runs every case on every model (each on `threads` threads, with `inference`);
// `progress` (may be empty) gets each result with the number of results done and their total.
std::vector<ModelResults> ValidateSuite(
    const std::vector<const GaitModel*>& models, const std::vector<std::string>& model_names,
    const GaitDataset& dataset, const std::vector<ValidationCase>& cases, const InferenceOptions& inference, int threads,
    const std::function<void(const ModelResults&, size_t done, size_t total)>& progress = {});

// Estimated poses against true ones (both T x D, degrees) on one skeleton: the mean over
// poses of each of the 17 measured joints' distance (mm), their mean, and each channel's
// mean absolute angle difference (degrees, taken the short way round).
struct PoseErrors {
  double mean_mm = 0;
  Eigen::VectorXd joint_mm, channel_deg;
};
PoseErrors ComparePoses(const GaitPoseKinematics& kinematics, const Eigen::MatrixXd& estimated,
                        const Eigen::MatrixXd& truth);
// ComparePoses(...).mean_mm.
double MeanJointErrorMm(const GaitPoseKinematics& kinematics, const Eigen::MatrixXd& estimated,
                        const Eigen::MatrixXd& truth);

// The paper's experiments, each at stride scales 1.25, 1, 0.667, 0.5 and 0.4:
// interpolation; reconstruction without the left arm, left leg and left side; filtering
// at 5%, 10% and 15% noise with 5 draws.
std::vector<ValidationCase> PaperSuite();

}  // namespace jgpm
