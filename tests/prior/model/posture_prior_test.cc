// The posture prior against its definition (prior/model/posture_prior.h), computed here from the
// subject offsets the synthetic walks were made with: the spread of the subjects' mean
// postures, its correlations kept at weight c, the floor added; A A^T and W^T W against
// Sigma and its inverse (an LDLT solve). The leave-one-subject-out choice of c and the
// floor against a brute-force search written here, and against subjects whose postures
// are known to be uncorrelated (c = 0) or to move along one direction (c = 1).
#include "prior/model/posture_prior.h"

#include <numbers>

#include <Eigen/Cholesky>
#include <gtest/gtest.h>

#include "prior/learning/training_set.h"
#include "prior/prior_test_support.h"

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
  options.select = false;
  options.correlation_weight = 0.3;
  options.floor_deg = 1.5;
  const PosturePrior prior = PosturePrior::FromTrainingSet(set, options);
  EXPECT_EQ(prior.NumSubjects(), 4);
  EXPECT_FALSE(prior.selected());
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
  EXPECT_FALSE(prior.selected());  // too few subjects to hold one out
  const double floor = PosturePriorOptions{}.floor_deg;
  EXPECT_LT((prior.covariance() - floor * floor * Eigen::MatrixXd::Identity(kChannels, kChannels)).norm(), 1e-12);
}

// Each subject's mean log density given the others, with an LDLT and the Gaussian written out.
double BruteHeldOut(const Eigen::MatrixXd& offsets, double c, double floor) {  // subjects x D
  const int n = static_cast<int>(offsets.rows());
  double sum = 0;
  for (int held = 0; held < n; ++held) {
    Eigen::MatrixXd others(n - 1, kChannels);
    for (int s = 0, k = 0; s < n; ++s) {
      if (s != held) others.row(k++) = offsets.row(s);
    }
    const Eigen::RowVectorXd mean = others.colwise().mean();
    const Eigen::MatrixXd centred = others.rowwise() - mean;
    const Eigen::MatrixXd spread = centred.transpose() * centred / (n - 2.0);
    Eigen::MatrixXd sigma(kChannels, kChannels);
    for (int i = 0; i < kChannels; ++i) {
      for (int j = 0; j < kChannels; ++j) sigma(i, j) = i == j ? spread(i, i) + floor * floor : c * spread(i, j);
    }
    const Eigen::VectorXd r = (offsets.row(held) - mean).transpose();
    const Eigen::LDLT<Eigen::MatrixXd> ldlt(sigma);
    sum += -0.5 * (r.dot(ldlt.solve(r)) + ldlt.vectorD().array().log().sum() + kChannels * std::log(2 * std::numbers::pi));
  }
  return sum / n;
}

// The chosen pair is the grid's best by the brute-force score, and the prior is built with it.
void ExpectBestOfGrid(const Eigen::MatrixXd& offsets, const PosturePrior& prior) {
  ASSERT_TRUE(prior.selected());
  const double chosen = BruteHeldOut(offsets, prior.correlation_weight(), prior.floor_deg());
  for (const double c : kPostureCorrelationWeights) {
    for (const double floor : kPostureFloorsDeg) {
      const double score = BruteHeldOut(offsets, c, floor);
      EXPECT_LE(score, chosen + 1e-9 * std::abs(chosen)) << "c " << c << " floor " << floor;
      EXPECT_NEAR(HeldOutSubjectLogDensity(offsets.transpose(), c, floor), score, 1e-9 * std::abs(score));
    }
  }
  const Eigen::MatrixXd centred = offsets.rowwise() - offsets.colwise().mean();
  const Eigen::MatrixXd spread = centred.transpose() * centred / (offsets.rows() - 1.0);
  EXPECT_NEAR(prior.covariance()(0, 1), prior.correlation_weight() * spread(0, 1), 1e-9 * spread.maxCoeff());
  EXPECT_NEAR(prior.covariance()(2, 2), spread(2, 2) + std::pow(prior.floor_deg(), 2), 1e-9 * spread.maxCoeff());
}

TEST(PosturePrior, UncorrelatedSubjectsKeepNoCorrelations) {
  // Independent offsets per channel: correlations among 3 subjects are accidents.
  const Eigen::MatrixXd offsets = SubjectOffsets(4);
  const PosturePrior prior = PosturePrior::FromTrainingSet(
      MakeTrainingSet(test::SyntheticSubjectWalks(12, 10, offsets), {1.0}));
  ExpectBestOfGrid(offsets, prior);
  EXPECT_EQ(prior.correlation_weight(), 0.0);
}

TEST(PosturePrior, SubjectsAlongOneDirectionKeepTheirCorrelations) {
  // Every subject leans along the same direction v by its own amount: a held-out subject's
  // offset is predicted by the others' correlations, exactly.
  std::srand(9);
  const Eigen::RowVectorXd v = 6 * Eigen::RowVectorXd::Random(kChannels);
  const Eigen::VectorXd amount = Eigen::VectorXd::LinSpaced(6, -2, 2.5);
  const Eigen::MatrixXd offsets = amount * v;
  const TrainingSet set = MakeTrainingSet(test::SyntheticSubjectWalks(12, 10, offsets), {1.0});
  const PosturePrior prior = PosturePrior::FromTrainingSet(set);
  ExpectBestOfGrid(offsets, prior);
  EXPECT_EQ(prior.NumSubjects(), 6);
  EXPECT_EQ(prior.correlation_weight(), 1.0);
  // Its chosen options rebuild the same prior without choosing again.
  const PosturePrior again = PosturePrior::FromTrainingSet(set, prior.Chosen());
  EXPECT_FALSE(again.selected());
  EXPECT_EQ(again.covariance(), prior.covariance());
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
