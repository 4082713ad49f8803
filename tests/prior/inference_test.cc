// Sequence inference on small models of synthetic walks: the energy's gradient against
// finite differences, and recovery of sequences the model knows, from partial or noisy
// observations, against the poses that generated them.
#include "prior/inference.h"
#include "prior/pca_gait_model.h"

#include <random>

#include <gtest/gtest.h>

#include "prior_test_support.h"

namespace jgpm {
namespace {

using test::ExpectInputError;

// The layer of stride scale 1.
int UnscaledLayer(const TrainingSet& set) {
  return static_cast<int>(std::find(set.layer_scales.begin(), set.layer_scales.end(), 1.0) - set.layer_scales.begin());
}

// The poses of training cycle `gait` as the model itself reproduces them.
Eigen::MatrixXd ModelCycle(const GaitModel& model, int gait) {
  const TrainingSet& set = model.data().set;
  return model.MeanPoses(model.latent().middleRows(set.Row(UnscaledLayer(set), gait, 0), set.poses_per_gait));
}

// A cycle the model can represent but was not trained on: its mean poses halfway between
// the latent points of training cycles `gait` and `gait` + 1.
Eigen::MatrixXd BetweenCycles(const GaitModel& model, int gait) {
  const TrainingSet& set = model.data().set;
  const int p = set.poses_per_gait, layer = UnscaledLayer(set);
  return model.MeanPoses(0.5 * (model.latent().middleRows(set.Row(layer, gait, 0), p) +
                                model.latent().middleRows(set.Row(layer, gait + 1, 0), p)));
}

std::vector<bool> EveryThirdMissing(int channels) {
  std::vector<bool> observed(channels, true);
  for (int k = 0; k < channels; k += 3) observed[k] = false;
  return observed;
}

// Mean absolute difference in degrees over the channels flagged in `which` (all if empty).
double MeanAbsDeg(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b, const std::vector<bool>& which = {}) {
  double sum = 0;
  int count = 0;
  for (int k = 0; k < a.cols(); ++k) {
    if (!which.empty() && !which[k]) continue;
    sum += (a.col(k) - b.col(k)).cwiseAbs().sum();
    count += static_cast<int>(a.rows());
  }
  return sum / count;
}

TEST(Inference, EnergyGradientMatchesFiniteDifferences) {
  for (ModelKind kind : {ModelKind::kPca, ModelKind::kGplvm, ModelKind::kMljgpmTorus}) {
    SCOPED_TRACE(std::string(ModelKindName(kind)));
    const auto model = test::TrainOnSyntheticWalks(kind);
    PoseObservations observations;
    observations.poses_deg = ModelCycle(*model, 1) + Eigen::MatrixXd::Random(10, model->NumChannels());
    observations.observed = EveryThirdMissing(model->NumChannels());
    observations.noise_std_deg = Eigen::VectorXd::Constant(model->NumChannels(), 0.5);
    SequenceProblem energy(*model, observations, InferenceOptions{});
    const Eigen::MatrixXd x = model->latent().middleRows(3, 10) + 0.05 * Eigen::MatrixXd::Random(10, 3);
    Eigen::MatrixXd analytic;
    const double e = energy.Evaluate(x, &analytic);
    const double h = 1e-6;
    for (int t = 0; t < x.rows(); ++t) {
      for (int d = 0; d < 3; ++d) {
        Eigen::MatrixXd plus = x, minus = x;
        plus(t, d) += h;
        minus(t, d) -= h;
        const double fd = (energy.Evaluate(plus, nullptr) - energy.Evaluate(minus, nullptr)) / (2 * h);
        // Relative error, plus the rounding of E itself in the difference quotient.
        EXPECT_NEAR(analytic(t, d), fd, 1e-5 * std::max(1.0, std::abs(fd)) + 1e-13 * std::abs(e) / h) << t << " " << d;
      }
    }
  }
}

// A cycle the model can represent, with a third of its channels missing: the missing
// channels come back to within a small fraction of the channels' spread, much closer
// than from the nearest training poses the inference starts at. (Not exactly: the latent
// density pulls towards the training points, the more so the denser they are, as in the
// three-layer model: 0.02 deg for GPDM, 0.7 for ML-JGPM.)
TEST(Inference, RecoversMissingChannels) {
  for (ModelKind kind : {ModelKind::kGpdm, ModelKind::kMljgpmTorus}) {
    SCOPED_TRACE(std::string(ModelKindName(kind)));
    const auto model = test::TrainOnSyntheticWalks(kind);
    const Eigen::MatrixXd truth = BetweenCycles(*model, 2);
    PoseObservations observations;
    observations.poses_deg = truth;
    observations.observed = EveryThirdMissing(model->NumChannels());
    std::vector<bool> missing(observations.observed.size());
    for (size_t k = 0; k < missing.size(); ++k) missing[k] = !observations.observed[k];
    for (size_t k = 0; k < missing.size(); ++k) {
      if (missing[k]) observations.poses_deg.col(k).setConstant(std::nan(""));  // never read
    }
    const InferenceResult r = InferLatentSequence(*model, observations);
    EXPECT_LE(r.final_objective, r.initial_objective);
    const double spread = (truth.rowwise() - truth.colwise().mean()).cwiseAbs().mean();
    const double initial = MeanAbsDeg(model->MeanPoses(r.initial_latent), truth, missing);
    const double final = MeanAbsDeg(r.poses_deg, truth, missing);
    std::cout << ModelKindName(kind) << ": missing channels off by " << final << " deg (from "
              << initial << " at the start; spread " << spread << ")\n";
    EXPECT_LT(final, initial / 3);
    EXPECT_LT(final, 0.1 * spread);
  }
}

// Noisy observations of a known cycle: the estimate is closer to the truth than the input.
TEST(Inference, FiltersNoise) {
  const auto model = test::TrainOnSyntheticWalks(ModelKind::kGpdm);
  const Eigen::MatrixXd truth = BetweenCycles(*model, 3);
  std::mt19937 random(7);
  std::normal_distribution<double> normal(0, 1);
  const Eigen::RowVectorXd std_deg = (truth.rowwise() - truth.colwise().mean()).colwise().norm() / std::sqrt(10.0);
  PoseObservations observations;
  observations.noise_std_deg = 0.15 * std_deg.transpose();
  observations.poses_deg = truth;
  for (int t = 0; t < truth.rows(); ++t) {
    for (int k = 0; k < truth.cols(); ++k) observations.poses_deg(t, k) += observations.noise_std_deg[k] * normal(random);
  }
  const InferenceResult r = InferLatentSequence(*model, observations);
  EXPECT_LT(MeanAbsDeg(r.poses_deg, truth), 0.5 * MeanAbsDeg(observations.poses_deg, truth));
}

// A model whose predictions are not finite: Levenberg-Marquardt cannot take a step, and
// the result says so instead of passing NaN on.
class NanModel : public PcaGaitModel {
 public:
  using PcaGaitModel::MeanPoses;
  using PcaGaitModel::PcaGaitModel;
  Eigen::MatrixXd MeanPoses(const Eigen::MatrixXd& xs, std::array<Eigen::MatrixXd, 3>* jacobians) const override {
    Eigen::MatrixXd poses = PcaGaitModel::MeanPoses(xs, jacobians);
    poses(0, 0) = std::nan("");
    return poses;
  }
};

TEST(Inference, ReportsHowTheSolverEnded) {
  const auto pca = test::TrainOnSyntheticWalks(ModelKind::kPca);
  PoseObservations o;
  o.poses_deg = test::SyntheticWalks(1, 10).trials[0].cycle.poses;
  const InferenceResult good = InferLatentSequence(*pca, o);
  EXPECT_NE(good.termination, Termination::kNumericalFailure) << good.message;
  const NanModel nan_model(pca->data(), "nan");
  const InferenceResult bad = InferLatentSequence(nan_model, o);
  EXPECT_EQ(bad.termination, Termination::kNumericalFailure);
  EXPECT_FALSE(bad.message.empty());
}

TEST(Inference, BadInput) {
  const auto model = test::TrainOnSyntheticWalks(ModelKind::kPca);
  const int d = model->NumChannels();
  PoseObservations o;
  o.poses_deg = Eigen::MatrixXd::Zero(4, d - 1);
  ExpectInputError([&] { InferLatentSequence(*model, o); }, {"observed poses", "x 43 channels, got 4 x 42"});
  o.poses_deg = Eigen::MatrixXd::Zero(4, d);
  o.poses_deg(2, 5) = std::nan("");
  ExpectInputError([&] { InferLatentSequence(*model, o); }, {"observed poses", "pose 2", "is not finite"});
  o.observed.assign(d, false);
  ExpectInputError([&] { InferLatentSequence(*model, o); }, {"at least one channel must be observed"});
  o.observed.assign(d, true);
  o.observed[5] = false;  // the NaN is in a missing channel: fine
  EXPECT_TRUE(InferLatentSequence(*model, o).latent.allFinite());
  o.noise_std_deg = Eigen::VectorXd::Constant(d, -1);
  ExpectInputError([&] { InferLatentSequence(*model, o); }, {"observation noise", "standard deviations >= 0"});
  InferenceOptions bad;
  bad.observation_noise_deg = 0;
  o.noise_std_deg.resize(0);
  ExpectInputError([&] { InferLatentSequence(*model, o, bad); }, {"inference options", "observation_noise_deg"});
  EXPECT_FALSE(bad.Check(nullptr));  // `why` may be null
}

}  // namespace
}  // namespace jgpm
