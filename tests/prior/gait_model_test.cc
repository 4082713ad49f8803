#include "prior/gait_model.h"

#include <gtest/gtest.h>

#include "io/asf.h"
#include "io/text_reader.h"
#include "prior/model_file.h"
#include "prior/train.h"
#include "prior_test_support.h"
#include "test_support.h"

namespace jgpm {
namespace {

// The synthetic datasets use made-up channels, so models need a matching skeleton: the
// 43 gait channels of a real CMU skeleton, filled with synthetic walks.
GaitDataset SyntheticWalks(int gaits, int poses) {
  const Skeleton skeleton = [] {
    const std::string text = ReadTextFile(test::CmuRoot() / "subjects/35/35.asf", "asf");
    return ParseAsf(text, "35.asf");
  }();
  const GaitPoseLayout layout(skeleton, "35.asf");
  GaitDataset dataset = test::SyntheticGaitDataset(gaits, poses, layout.NumChannels());
  dataset.channel_names = layout.channel_names();
  dataset.channel_joints = layout.channel_joints();
  return dataset;
}

ReferenceSkeleton Skeleton35() {
  return {"35_01", ReadTextFile(test::CmuRoot() / "subjects/35/35.asf", "asf")};
}

std::unique_ptr<GaitModel> Train(ModelKind kind, Learning learning = Learning::kFull) {
  TrainingOptions options;
  options.kind = kind;
  options.learning = learning;
  options.full.max_iterations = 300;
  options.local.max_steps = 3000;
  options.local.max_neighbourhood_fraction = 0.5;
  return TrainGaitModel(SyntheticWalks(5, 10), Skeleton35(), options);
}

TEST(GaitModel, GpMeanReproducesTrainingPoses) {
  const auto model = Train(ModelKind::kGpdm);
  ASSERT_TRUE(model->data().summary.usable()) << model->data().summary.message;
  double worst = 0;
  for (int i = 0; i < model->NumPoints(); i += 7) {
    Eigen::VectorXd pose;
    double variance;
    model->Predict(model->latent().row(i).transpose(), &pose, &variance);
    worst = std::max(worst, (pose.transpose() - model->data().set.y_deg.row(i)).cwiseAbs().maxCoeff());
    EXPECT_LT(variance, 0.05);
  }
  // A GP with learned noise smooths: close to the data, not exactly on it.
  EXPECT_LT(worst, 3.0);
  // Far from the data the mean returns to the channel means and the variance to b1.
  Eigen::VectorXd far;
  double far_variance;
  model->Predict(Eigen::Vector3d(100, 100, 100), &far, &far_variance);
  EXPECT_LT((far.transpose() - model->data().set.mean).norm(), 1e-6);
  EXPECT_NEAR(far_variance, std::exp(model->data().params.log_beta[0]), 1e-9);
}

// LogPrior's gradient against central finite differences, for both variants.
TEST(GaitModel, LogPriorGradientMatchesFiniteDifferences) {
  for (ModelKind kind : {ModelKind::kPca, ModelKind::kJgpm}) {
    const auto model = Train(kind);
    for (int i = 3; i < model->NumPoints(); i += 11) {
      const Eigen::Vector3d x = model->latent().row(i).transpose() + Eigen::Vector3d(0.05, -0.03, 0.02);
      Eigen::Vector3d gradient;
      model->LogPrior(x, &gradient);
      for (int d = 0; d < 3; ++d) {
        Eigen::Vector3d plus = x, minus = x;
        plus[d] += 1e-6;
        minus[d] -= 1e-6;
        const double fd = (model->LogPrior(plus, nullptr) - model->LogPrior(minus, nullptr)) / 2e-6;
        EXPECT_NEAR(gradient[d], fd, 1e-4 * std::max(1.0, std::abs(fd))) << ModelKindName(kind) << " " << i;
      }
    }
    // Points on the data are more plausible than points far from it.
    EXPECT_GT(model->LogPrior(model->latent().row(0).transpose(), nullptr),
              model->LogPrior(Eigen::Vector3d(50, 50, 50), nullptr));
  }
}

TEST(GaitModel, BatchedVariancesMatchPredict) {
  const auto model = Train(ModelKind::kGplvm);
  Eigen::MatrixXd xs = Eigen::MatrixXd::Random(20, 3) * 2;
  const Eigen::VectorXd batched = model->Variances(xs);
  for (int i = 0; i < xs.rows(); ++i) {
    Eigen::VectorXd pose;
    double variance;
    model->Predict(xs.row(i).transpose(), &pose, &variance);
    EXPECT_NEAR(batched[i], variance, 1e-9);
  }
}

TEST(GaitModel, DynamicsStepFollowsTheTrainingSequences) {
  const auto model = Train(ModelKind::kGpdm);
  ASSERT_TRUE(model->HasDynamics());
  double error = 0, spacing = 0;
  for (int i = 0; i < model->NumPoints(); ++i) {
    if ((i + 1) % 10 == 0) continue;
    const Eigen::Vector3d next = model->NextLatent(model->latent().row(i).transpose(), nullptr);
    error += (next - model->latent().row(i + 1).transpose()).norm();
    spacing += (model->latent().row(i + 1) - model->latent().row(i)).norm();
  }
  EXPECT_LT(error, 0.2 * spacing);  // predicts the next point far better than standing still
}

TEST(GaitModel, ManifoldCoordinatesRoundTrip) {
  const auto model = Train(ModelKind::kMljgpmTorus);
  ASSERT_TRUE(model->HasManifold());
  const TrainingSet& set = model->data().set;
  // On the grid the interpolation gives the training latent points themselves.
  const std::vector<int>& order = model->data().gait_order;
  for (int layer = 0; layer < 3; ++layer) {
    const int g = order[2];
    const Eigen::Vector3d x = model->ManifoldToLatent({0.3, 2.0, set.layer_scales[layer]});
    EXPECT_LT((x - model->latent().row(set.Row(layer, g, 3)).transpose()).norm(), 1e-9);
  }
  // Between the grid points the inverse finds the coordinates again.
  for (const ManifoldPoint& m : {ManifoldPoint{0.42, 1.5, 0.7}, ManifoldPoint{0.05, 3.2, 1.1},
                                 ManifoldPoint{0.81, 4.6, 1.0}}) {
    const ManifoldPoint back = model->LatentToManifold(model->ManifoldToLatent(m));
    EXPECT_LT((model->ManifoldToLatent(back) - model->ManifoldToLatent(m)).norm(), 1e-6);
  }
  // The torus wraps in gait and in phase.
  EXPECT_LT((model->ManifoldToLatent({1.25, 5.5, 1}) - model->ManifoldToLatent({0.25, 0.5, 1})).norm(), 1e-12);
}

TEST(GaitModel, JointPositionsUseTheReferenceSkeleton) {
  const auto model = Train(ModelKind::kPca);
  Eigen::VectorXd pose;
  double variance;
  model->Predict(Eigen::Vector3d::Zero(), &pose, &variance);
  Eigen::Matrix3Xd joints;
  model->JointPositions(pose, &joints);
  ASSERT_EQ(joints.cols(), 17);
  EXPECT_TRUE(joints.allFinite());
  EXPECT_EQ(model->skeleton().bones.size(), 31u);
}

TEST(GaitModel, LocalLearningImprovesTheObjective) {
  const auto model = Train(ModelKind::kMljgpmTorus, Learning::kLocal);
  const TrainingSummary& s = model->data().summary;
  EXPECT_EQ(s.learning, "local");
  EXPECT_LT(s.final_objective, s.initial_objective);
}

TEST(GaitModel, SameSeedSameModel) {
  const auto a = Train(ModelKind::kJgpm, Learning::kLocal);
  const auto b = Train(ModelKind::kJgpm, Learning::kLocal);
  EXPECT_EQ(a->latent(), b->latent());
  EXPECT_EQ(a->data().params.log_w, b->data().params.log_w);
  const auto c = Train(ModelKind::kGplvm);
  const auto d = Train(ModelKind::kGplvm);
  EXPECT_EQ(c->latent(), d->latent());
}

}  // namespace
}  // namespace jgpm
