#include "prior/model/gait_model.h"

#include <gtest/gtest.h>

#include "io/mocap/asf.h"
#include "io/mocap/kinematics.h"
#include "prior/learning/topology.h"
#include "prior/model/model_file.h"
#include "prior/model/model_kind.h"
#include "prior/model/train.h"
#include "prior/prior_test_support.h"
#include "test_support.h"

namespace jgpm {
namespace {

std::unique_ptr<GaitModel> Train(ModelKind kind, Learning learning = Learning::kFull) {
  return test::TrainOnSyntheticWalks(kind, learning);
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

// MeanPoses row by row equals Predict, and its Jacobians equal central finite
// differences, for both variants.
TEST(GaitModel, BatchedMeanPosesAndTheirJacobians) {
  for (ModelKind kind : {ModelKind::kPca, ModelKind::kGpdm}) {
    const auto model = Train(kind);
    Eigen::MatrixXd xs = model->latent().topRows(6) + 0.1 * Eigen::MatrixXd::Random(6, 3);
    std::array<Eigen::MatrixXd, 3> jacobians;
    const Eigen::MatrixXd poses = model->MeanPoses(xs, &jacobians);
    for (int t = 0; t < xs.rows(); ++t) {
      Eigen::VectorXd pose;
      model->Predict(xs.row(t).transpose(), &pose, nullptr);
      EXPECT_LT((poses.row(t).transpose() - pose).cwiseAbs().maxCoeff(), 1e-9) << ModelKindName(kind);
      for (int d = 0; d < 3; ++d) {
        Eigen::MatrixXd plus = xs, minus = xs;
        plus(t, d) += 1e-6;
        minus(t, d) -= 1e-6;
        const Eigen::RowVectorXd fd = (model->MeanPoses(plus).row(t) - model->MeanPoses(minus).row(t)) / 2e-6;
        EXPECT_LT((jacobians[d].row(t) - fd).cwiseAbs().maxCoeff(), 1e-5 * std::max(1.0, fd.cwiseAbs().maxCoeff()))
            << ModelKindName(kind);
      }
    }
  }
}

TEST(GaitModel, DynamicsJacobianMatchesFiniteDifferences) {
  const auto model = Train(ModelKind::kGpdm);
  for (int i = 2; i < model->NumPoints(); i += 13) {
    const Eigen::Vector3d x = model->latent().row(i).transpose() + Eigen::Vector3d(0.03, 0.02, -0.04);
    Eigen::Matrix3d jacobian;
    model->NextLatent(x, nullptr, &jacobian);
    for (int d = 0; d < 3; ++d) {
      Eigen::Vector3d plus = x, minus = x;
      plus[d] += 1e-6;
      minus[d] -= 1e-6;
      const Eigen::Vector3d fd = (model->NextLatent(plus, nullptr) - model->NextLatent(minus, nullptr)) / 2e-6;
      EXPECT_LT((jacobian.col(d) - fd).norm(), 1e-5 * std::max(1.0, fd.norm())) << i;
    }
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

// The dynamics GP is built on a thread of its own while the mapping's is built: a model
// built again from its data predicts the same numbers, and an error found on that thread
// reaches the caller as one InputError naming the model.
TEST(GaitModel, DynamicsBuiltBesideTheMappingAreTheSameAndReportTheirErrors) {
  const auto model = Train(ModelKind::kGpdm);
  ASSERT_TRUE(model->HasDynamics());
  const auto again = GaitModel::Create(model->data(), "again.json");
  for (int i = 0; i < model->NumPoints(); i += 11) {
    const Eigen::Vector3d x = model->latent().row(i).transpose();
    EXPECT_EQ(again->NextLatent(x, nullptr), model->NextLatent(x, nullptr)) << i;
    Eigen::VectorXd a, b;
    double va, vb;
    model->Predict(x, &a, &va);
    again->Predict(x, &b, &vb);
    EXPECT_EQ(a, b) << i;
    EXPECT_EQ(va, vb) << i;
  }
  GaitModelData overflowing = model->data();
  overflowing.params.log_alpha.setConstant(800);  // finite, but exp() of it is not
  test::ExpectInputError([&] { GaitModel::Create(overflowing, "broken.json"); }, {"broken.json", "dynamics kernel"});
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

// The end of bone `b` in the rest pose (every angle zero), by hand: the root's position
// plus direction x length of every bone down the chain, in millimetres (ASF lengths are
// inches times the `:units length` factor).
Eigen::Vector3d RestPositionMm(const Skeleton& skeleton, int b) {
  const double mm_per_unit = 25.4 / skeleton.length_scale;
  Eigen::Vector3d end = skeleton.root_position * mm_per_unit;
  for (; b > 0; b = skeleton.bones[b].parent) end += skeleton.bones[b].direction * skeleton.bones[b].length * mm_per_unit;
  return end;
}

// JointPositions against forward kinematics done here, on subject 35's skeleton (the
// reference the synthetic walks train with), parsed here from its ASF: the rest pose by
// hand, and a walking pose through Kinematics with the pose's channels put into a frame by
// name. Joint j (1..17) is the end of the last bone of GaitJoints()[j].
TEST(GaitModel, JointPositionsAreForwardKinematicsOfTheReferenceSkeleton) {
  const auto model = Train(ModelKind::kPca);
  const Skeleton skeleton = ParseAsf(test::Skeleton35().asf, "35.asf");
  std::vector<int> ends;
  for (size_t j = 1; j < GaitJoints().size(); ++j) ends.push_back(skeleton.FindBone(GaitJoints()[j].bones.back()));
  ASSERT_EQ(ends.size(), 17u);
  Eigen::Matrix3Xd rest(3, 17), joints;
  for (int j = 0; j < 17; ++j) rest.col(j) = RestPositionMm(skeleton, ends[j]);
  // Millimetres: the top of the head (joint 5) is about 1.7 m above the left foot (8).
  EXPECT_NEAR(rest(1, 4) - rest(1, 7), 1700, 150);

  model->JointPositions(Eigen::VectorXd::Zero(model->NumChannels()), &joints);
  ASSERT_EQ(joints.cols(), 17);
  for (int j = 0; j < 17; ++j) EXPECT_LT((joints.col(j) - rest.col(j)).norm(), 1e-9) << GaitJoints()[j + 1].name;

  Eigen::VectorXd pose;
  model->Predict(model->latent().row(3).transpose(), &pose, nullptr);
  ASSERT_GT(pose.cwiseAbs().maxCoeff(), 10.0);  // a pose far from the rest pose
  std::vector<double> frame(skeleton.NumChannels(), 0.0);
  const std::vector<std::string> names = skeleton.ChannelNames();
  for (int c = 0; c < model->NumChannels(); ++c) {
    const auto at = std::find(names.begin(), names.end(), model->data().set.channel_names[c]);
    ASSERT_NE(at, names.end()) << model->data().set.channel_names[c];
    frame[at - names.begin()] = pose[c];
  }
  const Eigen::Matrix3Xd all = Kinematics(skeleton).Compute(frame.data());
  model->JointPositions(pose, &joints);
  for (int j = 0; j < 17; ++j) {
    EXPECT_LT((joints.col(j) - all.col(ends[j])).norm(), 1e-9) << GaitJoints()[j + 1].name;
  }
  EXPECT_GT((joints - rest).colwise().norm().maxCoeff(), 100.0);  // the pose moved the joints
}

// Local learning through TrainGaitModel: the model holds the parameters its summary
// reports. The objective is rebuilt here from the kind's spec (three layers of the walks,
// the torus topology, one sequence per cycle) and evaluated at the documented start (the
// topology's coordinates, b = (1, 1, 100), a = (1, 1, 0.1, 1e4), W = 1) and at the model's
// parameters; they give the summary's two objectives, the second far below the first.
// How close local learning comes to the optimum is checked where one is known in closed
// form (trainer_test.cc, LocalTrainer.ApproachesTheLinearGplvmOptimum): on these
// noiseless walks the RBF models' objective has none within reach (full learning still
// falls after 3000 iterations).
TEST(GaitModel, LocalLearningKeepsTheParametersItReports) {
  const auto model = Train(ModelKind::kMljgpmTorus, Learning::kLocal);
  const TrainingSummary& s = model->data().summary;
  EXPECT_EQ(s.learning, Learning::kLocal);
  const GaitDataset walks = test::SyntheticWalks(5, 10);
  const ModelSpec spec = SpecFor(ModelKind::kMljgpmTorus, static_cast<int>(walks.channel_names.size()));
  const TrainingSet set = MakeTrainingSet(walks, spec.layer_scales);
  ASSERT_EQ(set.y, model->data().set.y);
  TopologyOptions topology_options;
  topology_options.shape = spec.shape;
  const Topology topology = MakeTopology(set, topology_options);
  std::vector<Sequence> cycles;
  for (int c = 0; c < set.NumLayers() * set.NumGaits(); ++c) cycles.push_back({c * set.poses_per_gait, set.poses_per_gait});
  ObjectiveTerms terms = spec.terms;
  terms.topology_sigma2 = TrainingOptions{}.topology_sigma2;
  const GpObjective objective(set.y, cycles, &topology, terms);
  GpParameters start;
  start.x = topology.coordinates;
  start.log_beta = Eigen::Vector3d(0, 0, std::log(100.0));
  start.log_alpha = Eigen::Vector4d(0, 0, std::log(0.1), std::log(1e4));
  start.log_w = Eigen::VectorXd::Zero(set.NumChannels());
  EXPECT_NEAR(objective.Evaluate(start, nullptr).total, s.initial_objective, 1e-9 * std::abs(s.initial_objective));
  EXPECT_NEAR(objective.Evaluate(model->data().params, nullptr).total, s.final_objective,
              1e-9 * std::abs(s.final_objective));
  EXPECT_LT(s.final_objective, s.initial_objective - 0.5 * std::abs(s.initial_objective)) << s.BriefReport();
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
