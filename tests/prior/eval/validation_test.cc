// Model validation: the joint-error measure against geometry, the paper's case list, and
// Validate on a small model of synthetic walks whose training cycles it must reproduce.
#include "prior/eval/validation.h"

#include <cmath>
#include <numbers>
#include <set>

#include <gtest/gtest.h>

#include "io/gait/split.h"
#include "prior/model/pca_gait_model.h"
#include "prior/numerics/blas_threads.h"
#include "prior/prior_test_support.h"

namespace jgpm {
namespace {

using test::ExpectInputError;

std::shared_ptr<const GaitPoseKinematics> Kinematics35() {
  return std::make_shared<GaitPoseKinematics>(ParseAsf(test::Skeleton35().asf, "35.asf"), "35.asf");
}

int Channel(const GaitPoseLayout& layout, const std::string& name) {
  const auto& names = layout.channel_names();
  const auto it = std::find(names.begin(), names.end(), name);
  EXPECT_NE(it, names.end()) << name;
  return static_cast<int>(it - names.begin());
}

// Turning the whole body by theta about the vertical axis through the root (the root has
// no other rotation, so its ry channel is that turn) moves each joint along a chord of its
// circle about the axis: 2 sin(theta/2) times its horizontal distance from the axis.
TEST(MeanJointErrorMm, MatchesChordsOfATurnAboutTheVerticalAxis) {
  const auto kinematics = Kinematics35();
  const GaitPoseLayout& layout = kinematics->layout();
  const GaitDataset walks = test::SyntheticWalks(2, 6);
  Eigen::MatrixXd truth = walks.trials[0].cycle.poses;
  truth.col(Channel(layout, "root.rx")).setZero();
  truth.col(Channel(layout, "root.rz")).setZero();
  const double theta_deg = 30;
  Eigen::MatrixXd turned = truth;
  turned.col(Channel(layout, "root.ry")).array() += theta_deg;

  double expected = 0;
  Eigen::Matrix3Xd joints;
  for (int t = 0; t < truth.rows(); ++t) {
    const Eigen::VectorXd pose = truth.row(t).transpose();
    kinematics->Compute(pose.data(), &joints);
    const Eigen::VectorXd horizontal = (joints.row(0).array().square() + joints.row(2).array().square()).sqrt();
    expected += 2 * std::sin(theta_deg * std::numbers::pi / 360) * horizontal.mean() / truth.rows();
  }
  EXPECT_GT(expected, 10.0);
  EXPECT_NEAR(MeanJointErrorMm(*kinematics, turned, truth), expected, 1e-9 * expected);
  EXPECT_EQ(MeanJointErrorMm(*kinematics, truth, truth), 0.0);
}

// Where an error comes from. One channel changed by 7 degrees (and once by 350 degrees
// the other way, which is 10 degrees): that channel's angle error is exactly that and all
// others are 0; the joints above it in the chain do not move, the ones below do; and the
// per-joint errors average to the mean joint error.
TEST(ComparePoses, PerJointAndPerChannelErrorsSayWhereTheErrorIs) {
  const auto kinematics = Kinematics35();
  const GaitPoseLayout& layout = kinematics->layout();
  const Eigen::MatrixXd truth = test::SyntheticWalks(2, 6).trials[0].cycle.poses;
  const int knee = Channel(layout, "ltibia.rx");
  Eigen::MatrixXd bent = truth;
  bent.col(knee).array() += 7;
  bent(0, knee) = truth(0, knee) - 350;  // 10 degrees the short way round
  const PoseErrors e = ComparePoses(*kinematics, bent, truth);
  ASSERT_EQ(e.joint_mm.size(), 17);
  ASSERT_EQ(e.channel_deg.size(), truth.cols());
  for (int k = 0; k < truth.cols(); ++k) {
    EXPECT_NEAR(e.channel_deg[k], k == knee ? (7.0 * (truth.rows() - 1) + 10) / truth.rows() : 0.0, 1e-9) << k;
  }
  EXPECT_NEAR(e.mean_mm, e.joint_mm.mean(), 1e-12);
  EXPECT_NEAR(e.mean_mm, MeanJointErrorMm(*kinematics, bent, truth), 1e-12);
  // GaitJoints() 1..17 stand for the ends of their bones: the knee bend moves the end of
  // the shin (the ankle) and of the foot, and nothing else.
  for (int j = 1; j < static_cast<int>(GaitJoints().size()); ++j) {
    const std::string_view name = GaitJoints()[j].name;
    if (name == "ltibia" || name == "lfoot") {
      EXPECT_GT(e.joint_mm[j - 1], 1.0) << name;
    } else {
      EXPECT_LT(e.joint_mm[j - 1], 1e-9) << name;
    }
  }
}

TEST(ValidationCase, PaperSuiteAndChecks) {
  const std::vector<ValidationCase> suite = PaperSuite();
  ASSERT_EQ(suite.size(), 5u * 7u);  // 5 scales x (interpolation, 3 reconstructions, 3 noise levels)
  std::set<std::string> labels;
  std::string why;
  for (const ValidationCase& c : suite) {
    EXPECT_TRUE(c.Check(&why)) << c.Label() << ": " << why;
    labels.insert(c.Label());
    if (c.task == ValidationTask::kFiltering) {
      EXPECT_EQ(c.draws, 5);
    }
  }
  EXPECT_EQ(labels.size(), suite.size());
  EXPECT_TRUE(labels.count("interpolation s=0.667"));
  EXPECT_TRUE(labels.count("reconstruction left-side s=1.25"));
  EXPECT_TRUE(labels.count("filtering 15% s=0.4"));

  EXPECT_FALSE((ValidationCase{ValidationTask::kReconstruction, 1, MissingPart::kNone}).Check(&why));
  EXPECT_FALSE((ValidationCase{ValidationTask::kInterpolation, 1, MissingPart::kLeftArm}).Check(&why));
  EXPECT_FALSE((ValidationCase{ValidationTask::kFiltering, 1, MissingPart::kNone, 0}).Check(&why));
  EXPECT_FALSE((ValidationCase{ValidationTask::kInterpolation, -1}).Check(&why));
  EXPECT_FALSE((ValidationCase{ValidationTask::kInterpolation, -1}).Check(nullptr));  // `why` may be null
  EXPECT_FALSE((ValidationCase{ValidationTask::kInterpolation, 1, MissingPart::kNone, 0.1}).Check(&why));
}

TEST(MissingJoints, ArmLegAndSideOfTheLeft) {
  std::set<std::string_view> known;
  for (const GaitJoint& j : GaitJoints()) known.insert(j.name);
  const auto arm = MissingJoints(MissingPart::kLeftArm), leg = MissingJoints(MissingPart::kLeftLeg);
  const auto side = MissingJoints(MissingPart::kLeftSide);
  EXPECT_EQ(arm.size(), 3u);
  EXPECT_EQ(leg.size(), 3u);
  EXPECT_EQ(std::set<std::string_view>(side.begin(), side.end()).size(), 6u);
  for (std::string_view j : side) {
    EXPECT_TRUE(known.count(j)) << j;
    EXPECT_EQ(j[0], 'l') << j;
  }
  EXPECT_TRUE(MissingJoints(MissingPart::kNone).empty());
}

// The model's own training cycles: interpolation must give back about the training
// reconstruction error; hiding joints and adding noise cost more; the result does not
// depend on the thread count.
TEST(Validate, TrainingCyclesComeBackAndHarderCasesCostMore) {
  const auto model = test::TrainOnSyntheticWalks(ModelKind::kJgpm);
  const auto kinematics = Kinematics35();
  const GaitDataset walks = test::SyntheticWalks(5, 10);
  std::vector<ValidationTrial> trials;
  for (const GaitTrial& t : walks.trials) trials.push_back({t.id.name, t.cycle.poses, kinematics});

  const ValidationCase interpolation{ValidationTask::kInterpolation, 1.0};
  const ValidationResult a = Validate(*model, trials, interpolation, {}, 1);
  const ValidationResult b = Validate(*model, trials, interpolation, {}, 2);
  EXPECT_EQ(a.trial_errors_mm, b.trial_errors_mm);
  ASSERT_EQ(a.trial_errors_mm.size(), trials.size());
  double training_error = 0;
  for (size_t i = 0; i < trials.size(); ++i) {
    const Eigen::MatrixXd reproduced = model->MeanPoses(model->latent().middleRows(10 * i, 10));
    training_error += MeanJointErrorMm(*kinematics, reproduced, trials[i].poses_deg) / trials.size();
  }
  EXPECT_LT(a.mean_error_mm, training_error + 2.0) << "training reconstruction " << training_error;
  double mean = 0;
  for (double e : a.trial_errors_mm) mean += e / a.trial_errors_mm.size();
  EXPECT_NEAR(a.mean_error_mm, mean, 1e-12);
  // The per-joint errors average to the reported mean; every channel is named.
  ASSERT_EQ(a.joint_names.size(), 17u);
  ASSERT_EQ(a.joint_errors_mm.size(), 17u);
  double joints = 0;
  for (double e : a.joint_errors_mm) joints += e / 17;
  EXPECT_NEAR(joints, a.mean_error_mm, 1e-9);
  EXPECT_EQ(a.channel_names, model->data().set.channel_names);
  EXPECT_EQ(a.channel_errors_deg.size(), a.channel_names.size());

  const ValidationResult side =
      Validate(*model, trials, {ValidationTask::kReconstruction, 1.0, MissingPart::kLeftSide}, {}, 2);
  EXPECT_GT(side.mean_error_mm, a.mean_error_mm);
  const ValidationResult low = Validate(*model, trials, {ValidationTask::kFiltering, 1.0, MissingPart::kNone, 0.05, 3}, {}, 2);
  const ValidationResult high = Validate(*model, trials, {ValidationTask::kFiltering, 1.0, MissingPart::kNone, 0.3, 3}, {}, 2);
  ASSERT_EQ(high.draw_errors_mm.size(), 3u);
  EXPECT_GT(high.mean_error_mm, low.mean_error_mm);
  EXPECT_GT(high.std_error_mm, 0.0);  // different draws, different errors

  ExpectInputError([&] { Validate(*model, trials, {ValidationTask::kFiltering, 1.0}); }, {"filtering", "noise"});
}

// A model whose every prediction fails the way an allocation can (not an InputError).
class FailingModel : public PcaGaitModel {
 public:
  using PcaGaitModel::MeanPoses;
  using PcaGaitModel::PcaGaitModel;
  Eigen::MatrixXd MeanPoses(const Eigen::MatrixXd&, std::array<Eigen::MatrixXd, 3>*) const override {
    throw std::runtime_error("no memory for the kernel");
  }
};

// Any exception in a worker reaches the caller (it ended the process in std::terminate),
// and the OpenBLAS thread count the workers ran with is the caller's again afterwards.
TEST(Validate, WorkerExceptionsReachTheCallerAndThreadsAreRestored) {
  const auto pca = test::TrainOnSyntheticWalks(ModelKind::kPca);
  const FailingModel model(pca->data(), "failing");
  const auto kinematics = Kinematics35();
  const GaitDataset walks = test::SyntheticWalks(4, 10);
  std::vector<ValidationTrial> trials;
  for (const GaitTrial& t : walks.trials) trials.push_back({t.id.name, t.cycle.poses, kinematics});
  const LinearAlgebraThreadScope two(2);
  try {
    Validate(model, trials, {ValidationTask::kInterpolation, 1.0}, {}, 2);
    ADD_FAILURE() << "expected the model's exception";
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(), "no memory for the kernel");
  }
  EXPECT_EQ(LinearAlgebraThreads(), 2);
  Validate(*pca, trials, {ValidationTask::kInterpolation, 1.0}, {}, 2);
  EXPECT_EQ(LinearAlgebraThreads(), 2);
}

// The test split's clean cycles load with each subject's own skeleton.
TEST(LoadValidationTrials, TestSplitWithEachSubjectsSkeleton) {
  const auto model = test::TrainOnSyntheticWalks(ModelKind::kPca);
  const GaitDataset dataset = PrepareGaitDataset(test::CmuRoot(), "test", test::SplitTrials("test"), GaitCycleOptions{});
  const std::vector<ValidationTrial> trials = LoadValidationTrials(dataset, *model);
  ASSERT_EQ(static_cast<int>(trials.size()), dataset.NumClean());
  std::set<const GaitPoseKinematics*> skeletons;
  for (const ValidationTrial& t : trials) {
    skeletons.insert(t.kinematics.get());
    EXPECT_EQ(t.poses_deg.cols(), model->NumChannels());
  }
  EXPECT_EQ(skeletons.size(), 3u);  // subjects 07, 35, 39
}

}  // namespace
}  // namespace jgpm
