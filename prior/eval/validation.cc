#include "prior/eval/validation.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <exception>
#include <filesystem>
#include <map>
#include <random>
#include <thread>

#include "io/base/enum_name.h"
#include "io/base/error.h"
#include "io/base/text_reader.h"
#include "io/mocap/asf.h"
#include "prior/learning/training_set.h"
#include "prior/model/posture_prior.h"
#include "prior/numerics/blas_threads.h"

namespace jgpm {
namespace {

double StdDev(const std::vector<double>& v) {
  if (v.size() < 2) return 0;
  double mean = 0, sum = 0;
  for (double x : v) mean += x / v.size();
  for (double x : v) sum += (x - mean) * (x - mean);
  return std::sqrt(sum / (v.size() - 1));
}

double Mean(const std::vector<double>& v) {
  double sum = 0;
  for (double x : v) sum += x;
  return v.empty() ? 0 : sum / v.size();
}

struct TrialOutcome {
  PoseErrors errors;
  Eigen::VectorXd posture_deg;  // the offset inference found (zero without adaptation)
  Eigen::VectorXd gain;         // and the gains (ones)
  bool failed = false;          // inference ended in a numerical failure
};

// Error of one trial under one case, for noise draw `draw` (filtering; 0 otherwise).
TrialOutcome TrialError(const GaitModel& model, const ValidationTrial& trial, int trial_index,
                  const ValidationCase& c, int draw, const InferenceOptions& inference) {
  const Eigen::MatrixXd truth = ScaleGait(trial.poses_deg, c.scale);
  const int d = static_cast<int>(truth.cols());
  PoseObservations observations;
  observations.poses_deg = truth;
  if (c.task == ValidationTask::kReconstruction) {
    const std::vector<std::string_view> joints = MissingJoints(c.missing);
    const std::vector<int>& channel_joints = model.data().set.channel_joints;
    observations.observed.assign(d, true);
    for (int k = 0; k < d; ++k) {
      const std::string_view joint = GaitJoints()[channel_joints[k]].name;
      if (std::find(joints.begin(), joints.end(), joint) != joints.end()) observations.observed[k] = false;
    }
  }
  if (c.task == ValidationTask::kFiltering) {
    const Eigen::RowVectorXd channel_std =
        ((truth.rowwise() - truth.colwise().mean()).colwise().squaredNorm() / truth.rows()).cwiseSqrt();
    observations.noise_std_deg = c.noise * channel_std.transpose();
    std::mt19937_64 random(1000003ULL * draw + trial_index);
    std::normal_distribution<double> normal(0, 1);
    for (int t = 0; t < truth.rows(); ++t) {
      for (int k = 0; k < d; ++k) observations.poses_deg(t, k) += observations.noise_std_deg[k] * normal(random);
    }
  }
  const InferenceResult result = InferLatentSequence(model, observations, inference);
  if (!result.poses_deg.allFinite()) ThrowInputError("inference", result.message);
  return {ComparePoses(*trial.kinematics, result.poses_deg, truth), result.posture_deg, result.gain,
          result.termination == Termination::kNumericalFailure};
}

}  // namespace

std::string_view ValidationTaskName(ValidationTask task) {
  switch (task) {
    case ValidationTask::kInterpolation: return "interpolation";
    case ValidationTask::kReconstruction: return "reconstruction";
    case ValidationTask::kFiltering: return "filtering";
  }
  return "?";
}

bool ParseValidationTask(std::string_view name, ValidationTask* task) {
  return ParseByName(name, {ValidationTask::kInterpolation, ValidationTask::kReconstruction, ValidationTask::kFiltering},
                     ValidationTaskName, task);
}

std::string_view MissingPartName(MissingPart part) {
  switch (part) {
    case MissingPart::kNone: return "none";
    case MissingPart::kLeftArm: return "left-arm";
    case MissingPart::kLeftLeg: return "left-leg";
    case MissingPart::kLeftSide: return "left-side";
  }
  return "?";
}

bool ParseMissingPart(std::string_view name, MissingPart* part) {
  return ParseByName(name, {MissingPart::kNone, MissingPart::kLeftArm, MissingPart::kLeftLeg, MissingPart::kLeftSide},
                     MissingPartName, part);
}

std::vector<std::string_view> MissingJoints(MissingPart part) {
  const std::vector<std::string_view> arm = {"lhumerus", "lradius", "lwrist"};
  const std::vector<std::string_view> leg = {"lfemur", "ltibia", "lfoot"};
  switch (part) {
    case MissingPart::kNone: return {};
    case MissingPart::kLeftArm: return arm;
    case MissingPart::kLeftLeg: return leg;
    case MissingPart::kLeftSide: {
      std::vector<std::string_view> side = arm;
      side.insert(side.end(), leg.begin(), leg.end());
      return side;
    }
  }
  return {};
}

bool ValidationCase::Check(std::string* why) const {
  const char* problem = nullptr;
  if (!(scale > 0)) problem = "scale must be > 0";
  else if ((task == ValidationTask::kReconstruction) != (missing != MissingPart::kNone)) {
    problem = "missing joints go with reconstruction, and reconstruction needs them";
  } else if (task == ValidationTask::kFiltering && !(noise > 0)) problem = "filtering needs a noise level > 0";
  else if (task != ValidationTask::kFiltering && noise != 0) problem = "noise goes with filtering";
  else if (draws < 1) problem = "draws must be >= 1";
  if (problem && why) *why = problem;  // `why` may be null
  return problem == nullptr;
}

std::string ValidationCase::Label() const {
  char scale_text[32];
  std::snprintf(scale_text, sizeof(scale_text), " s=%g", scale);
  std::string label(ValidationTaskName(task));
  if (task == ValidationTask::kReconstruction) label += " " + std::string(MissingPartName(missing));
  if (task == ValidationTask::kFiltering) {
    char noise_text[32];
    std::snprintf(noise_text, sizeof(noise_text), " %g%%", 100 * noise);
    label += noise_text;
  }
  return label + scale_text;
}

std::vector<ValidationTrial> LoadValidationTrials(const GaitDataset& dataset, const GaitModel& model) {
  std::vector<ValidationTrial> trials;
  const std::vector<std::string>& channels = model.data().set.channel_names;
  std::map<std::string, std::shared_ptr<const GaitPoseKinematics>> skeletons;  // by ASF path
  for (const GaitTrial& trial : dataset.trials) {
    if (!trial.cycle.clean) continue;
    std::shared_ptr<const GaitPoseKinematics>& kinematics = skeletons[trial.asf];
    if (!kinematics) {
      const std::filesystem::path path = std::filesystem::path(dataset.data_root) / trial.asf;
      kinematics = std::make_shared<GaitPoseKinematics>(ParseAsf(ReadTextFile(path, "an ASF skeleton"), path.string()),
                                                        path.string());
      if (kinematics->layout().channel_names() != channels) {
        ThrowInputError(path.string(), "its gait channels differ from the model's");
      }
    }
    if (trial.cycle.poses.cols() != static_cast<int>(channels.size())) {
      ThrowInputError("dataset " + dataset.split, "trial " + trial.id.name + " has " +
                                                      std::to_string(trial.cycle.poses.cols()) + " channels, the model " +
                                                      std::to_string(channels.size()));
    }
    trials.push_back({trial.id.name, trial.cycle.poses, kinematics});
  }
  if (trials.empty()) ThrowInputError("dataset " + dataset.split, "has no clean gait cycle to validate on");
  return trials;
}

ValidationResult Validate(const GaitModel& model, const std::vector<ValidationTrial>& trials,
                          const ValidationCase& c, const InferenceOptions& options, int threads) {
  std::string why;
  if (!c.Check(&why)) ThrowInputError("validation case " + c.Label(), why);
  // The posture prior depends on the model alone: its c and floor are chosen once here, not
  // again for every trial's inference.
  InferenceOptions inference = options;
  if (inference.adapt_posture) {
    inference.posture = PosturePrior::FromTrainingSet(model.data().set, inference.posture).Chosen();
  }
  const auto start = std::chrono::steady_clock::now();
  const int n = static_cast<int>(trials.size());
  const int draws = c.task == ValidationTask::kFiltering ? c.draws : 1;
  // outcomes[i * draws + k]: trial i, draw k. Workers take trials by index, so the result
  // is the same for any number of threads.
  std::vector<TrialOutcome> outcomes(static_cast<size_t>(n) * draws);
  // Any exception in a worker is carried to this thread and rethrown there (the first
  // trial's, so which one is reported does not depend on the thread count); an escaping
  // exception would end the process.
  std::vector<std::exception_ptr> failures(n);
  auto work = [&](int worker, int workers) {
    for (int i = worker; i < n; i += workers) {
      try {
        for (int k = 0; k < draws; ++k) outcomes[i * draws + k] = TrialError(model, trials[i], i, c, k + 1, inference);
      } catch (...) {
        failures[i] = std::current_exception();
      }
    }
  };
  const int workers = std::max(1, std::min(threads, n));
  {
    // The trials run in parallel, so each keeps to one BLAS thread.
    const LinearAlgebraThreadScope one_blas_thread(1);
    std::vector<std::thread> pool;
    for (int w = 1; w < workers; ++w) pool.emplace_back(work, w, workers);
    work(0, workers);
    for (std::thread& t : pool) t.join();
  }
  for (int i = 0; i < n; ++i) {
    if (!failures[i]) continue;
    try {
      std::rethrow_exception(failures[i]);
    } catch (const InputError& e) {
      ThrowInputError("trial " + trials[i].id, e.what());
    }  // anything else propagates as it is
  }

  ValidationResult result;
  result.validation_case = c;
  auto error = [&](int i, int k) { return outcomes[i * draws + k].errors.mean_mm; };
  for (int i = 0; i < n; ++i) {
    result.trials.push_back(trials[i].id);
    double sum = 0;
    for (int k = 0; k < draws; ++k) sum += error(i, k);
    result.trial_errors_mm.push_back(sum / draws);
  }
  result.mean_error_mm = Mean(result.trial_errors_mm);
  // Per joint and channel: the mean over trials and draws, as mean_error_mm is.
  Eigen::VectorXd joint_mm = Eigen::VectorXd::Zero(outcomes[0].errors.joint_mm.size());
  Eigen::VectorXd channel_deg = Eigen::VectorXd::Zero(outcomes[0].errors.channel_deg.size());
  Eigen::VectorXd posture_deg = Eigen::VectorXd::Zero(channel_deg.size()), gain = posture_deg;
  const double count = static_cast<double>(outcomes.size());
  for (const TrialOutcome& o : outcomes) {
    joint_mm += o.errors.joint_mm / count;
    channel_deg += o.errors.channel_deg / count;
    posture_deg += o.posture_deg / count;
    gain += o.gain / count;
  }
  for (int j = 1; j < static_cast<int>(GaitJoints().size()); ++j) result.joint_names.emplace_back(GaitJoints()[j].name);
  result.channel_names = model.data().set.channel_names;
  result.joint_errors_mm.assign(joint_mm.data(), joint_mm.data() + joint_mm.size());
  result.channel_errors_deg.assign(channel_deg.data(), channel_deg.data() + channel_deg.size());
  if (inference.adapt_posture) {
    result.channel_posture_deg.assign(posture_deg.data(), posture_deg.data() + posture_deg.size());
    result.channel_gain.assign(gain.data(), gain.data() + gain.size());
  }
  result.inference_failures =
      static_cast<int>(std::count_if(outcomes.begin(), outcomes.end(), [](const TrialOutcome& o) { return o.failed; }));
  if (c.task == ValidationTask::kFiltering) {
    for (int k = 0; k < draws; ++k) {
      double sum = 0;
      for (int i = 0; i < n; ++i) sum += error(i, k);
      result.draw_errors_mm.push_back(sum / n);
    }
    result.std_error_mm = StdDev(result.draw_errors_mm);
  } else {
    result.std_error_mm = StdDev(result.trial_errors_mm);
  }
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

std::vector<ModelResults> ValidateSuite(
    const std::vector<const GaitModel*>& models, const std::vector<std::string>& model_names,
    const GaitDataset& dataset, const std::vector<ValidationCase>& cases, const InferenceOptions& inference, int threads,
    const std::function<void(const ModelResults&, size_t done, size_t total)>& progress) {
  JGPM_CHECK(models.size() == model_names.size());
  std::vector<ModelResults> suite;
  const size_t total = models.size() * cases.size();
  for (size_t m = 0; m < models.size(); ++m) {
    const std::vector<ValidationTrial> trials = LoadValidationTrials(dataset, *models[m]);
    ModelResults results{model_names[m], {}};
    for (const ValidationCase& c : cases) {
      results.results.push_back(Validate(*models[m], trials, c, inference, threads));
      if (progress) progress(results, m * cases.size() + results.results.size(), total);
    }
    suite.push_back(std::move(results));
  }
  return suite;
}

PoseErrors ComparePoses(const GaitPoseKinematics& kinematics, const Eigen::MatrixXd& estimated,
                        const Eigen::MatrixXd& truth) {
  JGPM_CHECK(estimated.rows() == truth.rows() && estimated.cols() == truth.cols() && truth.rows() > 0);
  PoseErrors e;
  Eigen::Matrix3Xd a, b;
  for (int t = 0; t < truth.rows(); ++t) {
    const Eigen::VectorXd x = estimated.row(t).transpose(), g = truth.row(t).transpose();
    kinematics.Compute(x.data(), &a);
    kinematics.Compute(g.data(), &b);
    const Eigen::VectorXd distances = (a - b).colwise().norm().transpose();
    if (t == 0) e.joint_mm = Eigen::VectorXd::Zero(distances.size());
    e.joint_mm += distances / static_cast<double>(truth.rows());
  }
  e.mean_mm = e.joint_mm.mean();
  // Angles wrap: 359 and 1 degrees are 2 apart.
  const Eigen::ArrayXXd d = (estimated - truth).array();
  e.channel_deg = (d - 360 * ((d + 180) / 360).floor()).abs().colwise().mean().matrix().transpose();
  return e;
}

double MeanJointErrorMm(const GaitPoseKinematics& kinematics, const Eigen::MatrixXd& estimated,
                        const Eigen::MatrixXd& truth) {
  return ComparePoses(kinematics, estimated, truth).mean_mm;
}

std::vector<ValidationCase> PaperSuite() {
  std::vector<ValidationCase> cases;
  for (double scale : {1.25, 1.0, 0.667, 0.5, 0.4}) {
    cases.push_back({ValidationTask::kInterpolation, scale, MissingPart::kNone, 0, 1});
    for (MissingPart part : {MissingPart::kLeftArm, MissingPart::kLeftLeg, MissingPart::kLeftSide}) {
      cases.push_back({ValidationTask::kReconstruction, scale, part, 0, 1});
    }
    for (double noise : {0.05, 0.10, 0.15}) cases.push_back({ValidationTask::kFiltering, scale, MissingPart::kNone, noise, 5});
  }
  return cases;
}

}  // namespace jgpm
