// The posture prior against its definition (prior/posture_prior.h), computed here from the
// subject offsets the synthetic walks were made with: the spread of the subjects' mean
// postures, its correlations kept at weight c, the floor added; A A^T and W^T W against
// Sigma and its inverse (an LDLT solve).
#include "prior/posture_prior.h"

#include <Eigen/Cholesky>
#include <gtest/gtest.h>

#include "prior/training_set.h"
#include "prior_test_support.h"

namespace jgpm {
namespace {

using test::ExpectInputError;

constexpr int kChannels = 43;  // the CMU skeleton's gait channels

Eigen::MatrixXd SubjectOffsets(int subjects) {
  std::srand(5);
  return 8 * Eigen::MatrixXd::Random(subjects, kChannels);
}

TEST(PosturePrior, IsTheSubjectsShrunkSpreadPlusTheFloor) {
  const Eigen::MatrixXd offsets = SubjectOffsets(4);
  // 12 gaits: 3 per subject, of several styles each; every gait's cycle mean is its
  // channel index plus its subject's offset (the walks' sines average out over a cycle).
  const TrainingSet set = MakeTrainingSet(test::SyntheticSubjectWalks(12, 10, offsets), {0.5, 1.0});
  PosturePriorOptions options;
  options.correlation_weight = 0.3;
  options.floor_deg = 1.5;
  const PosturePrior prior = PosturePrior::FromTrainingSet(set, options);
  EXPECT_EQ(prior.NumSubjects(), 4);
  const Eigen::MatrixXd centred = offsets.rowwise() - offsets.colwise().mean();
  const Eigen::MatrixXd spread = centred.transpose() * centred / 3.0;
  for (int i = 0; i < kChannels; ++i) {
    for (int j = 0; j < kChannels; ++j) {
      const double expected = i == j ? spread(i, i) + 1.5 * 1.5 : 0.3 * spread(i, j);
      ASSERT_NEAR(prior.covariance()(i, j), expected, 1e-9 * spread.maxCoeff()) << i << " " << j;
    }
  }
  const Eigen::MatrixXd& sigma = prior.covariance();
  EXPECT_LT((prior.root() * prior.root().transpose() - sigma).norm(), 1e-10 * sigma.norm());
  const Eigen::MatrixXd precision = sigma.ldlt().solve(Eigen::MatrixXd::Identity(kChannels, kChannels));
  EXPECT_LT((prior.whitening().transpose() * prior.whitening() - precision).norm(), 1e-10 * precision.norm());
  const Eigen::VectorXd delta = offsets.row(1).transpose();
  EXPECT_NEAR(prior.Energy(delta), 0.5 * delta.dot(sigma.ldlt().solve(delta)), 1e-9 * prior.Energy(delta));
  EXPECT_NEAR(prior.StdDeg()[7], std::sqrt(spread(7, 7) + 2.25), 1e-9);
}

TEST(PosturePrior, OneSubjectLeavesTheFloorAlone) {
  const TrainingSet set = MakeTrainingSet(test::SyntheticSubjectWalks(4, 10, SubjectOffsets(1)), {1.0});
  const PosturePrior prior = PosturePrior::FromTrainingSet(set);
  EXPECT_EQ(prior.NumSubjects(), 1);
  const double floor = PosturePriorOptions{}.floor_deg;
  EXPECT_LT((prior.covariance() - floor * floor * Eigen::MatrixXd::Identity(kChannels, kChannels)).norm(), 1e-12);
}

TEST(PosturePrior, BadInput) {
  const TrainingSet set = MakeTrainingSet(test::SyntheticSubjectWalks(4, 10, SubjectOffsets(2)), {1.0});
  PosturePriorOptions options;
  options.floor_deg = 0;
  ExpectInputError([&] { PosturePrior::FromTrainingSet(set, options); }, {"floor_deg"});
  options = {};
  options.correlation_weight = 1.5;
  ExpectInputError([&] { PosturePrior::FromTrainingSet(set, options); }, {"correlation_weight"});
  ExpectInputError([] { PosturePrior(Eigen::MatrixXd::Ones(3, 3)); }, {"positive definite"});
  ExpectInputError([] { PosturePrior(Eigen::MatrixXd::Identity(3, 2)); }, {"symmetric"});
  Eigen::MatrixXd nan = Eigen::MatrixXd::Identity(3, 3);
  nan(1, 1) = std::nan("");
  ExpectInputError([&] { PosturePrior{nan}; }, {"finite"});
}

}  // namespace
}  // namespace jgpm
