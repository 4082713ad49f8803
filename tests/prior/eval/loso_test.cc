// Leave-one-subject-out folds and their table (prior/eval/loso.h): each subject held out once,
// never in its own training set, the others capped per subject in split order; the
// table's mean rows against the mean of the subjects' rows, worked out here.
#include "prior/eval/loso.h"

#include <set>
#include <sstream>

#include <gtest/gtest.h>

#include "prior/prior_test_support.h"

namespace jgpm {
namespace {

TEST(Loso, FoldsHoldEachSubjectOutOnce) {
  // 10 gaits of subjects 91, 92, 93 (gait g is subject 91 + g % 3): 4, 3 and 3 trials.
  GaitDataset dataset = test::SyntheticSubjectWalks(10, 10, Eigen::MatrixXd::Zero(3, 43));
  dataset.trials[5].cycle.clean = false;  // one of 93's is not usable
  const std::vector<LosoFold> folds = LosoFolds(dataset, 2);
  ASSERT_EQ(folds.size(), 3u);
  for (const LosoFold& fold : folds) {
    std::map<std::string, int> per_subject;
    for (const GaitTrial& t : fold.train.trials) {
      EXPECT_NE(t.id.subject, fold.subject);
      EXPECT_TRUE(t.cycle.clean);
      ++per_subject[t.id.subject];
    }
    EXPECT_EQ(per_subject.size(), 2u);
    for (const auto& [subject, count] : per_subject) EXPECT_EQ(count, 2) << subject;
    for (const GaitTrial& t : fold.test.trials) EXPECT_EQ(t.id.subject, fold.subject);
  }
  EXPECT_EQ(folds[0].subject, "91");
  EXPECT_EQ(folds[0].test.trials.size(), 4u);
  EXPECT_EQ(folds[2].test.trials.size(), 2u);  // 93 without its unclean trial
  std::vector<std::string> taken;  // 91's, in fold 2: the first two in split order
  for (const GaitTrial& t : folds[1].train.trials) {
    if (t.id.subject == "91") taken.push_back(t.id.name);
  }
  EXPECT_EQ(taken, (std::vector<std::string>{"91_10", "91_13"}));

  GaitDataset one = test::SyntheticSubjectWalks(4, 10, Eigen::MatrixXd::Zero(1, 43));
  test::ExpectInputError([&] { LosoFolds(one, 9); }, {"at least two subjects", "has 1"});
  test::ExpectInputError([&] { LosoFolds(dataset, 0); }, {"at most 0"});
}

TEST(Loso, TableMeansWeighSubjectsAlike) {
  std::vector<LosoResult> results;
  const double errors[3] = {10, 20, 60};
  const int trials[3] = {1, 5, 2};
  for (int s = 0; s < 3; ++s) {
    for (bool adapted : {false, true}) {
      LosoResult r{std::to_string(91 + s), ModelKind::kPca, adapted, {}};
      r.validation.mean_error_mm = errors[s] / (adapted ? 2 : 1);
      r.validation.trials.assign(trials[s], "t");
      results.push_back(r);
    }
  }
  const std::string csv = LosoCsv(results);
  std::istringstream rows(csv);
  std::vector<std::string> lines;
  for (std::string row; std::getline(rows, row);) lines.push_back(row);
  ASSERT_EQ(lines.size(), 1u + 6 + 2);
  EXPECT_EQ(lines[0], "subject,model,adapted,trials,mean_error_mm,std_error_mm,seconds");
  EXPECT_EQ(lines[1].substr(0, 12), "91,pca,no,1,");
  // (10 + 20 + 60) / 3 = 30, sample std sqrt((400 + 100 + 900) / 2) = 26.458; halved.
  EXPECT_EQ(lines[7], "mean,pca,no,8,30.000,26.458,");
  EXPECT_EQ(lines[8], "mean,pca,yes,8,15.000,13.229,");
}

TEST(Loso, BadOptions) {
  LosoOptions options;
  std::string why;
  EXPECT_TRUE(options.Check(&why));
  options.kinds.clear();
  EXPECT_FALSE(options.Check(&why));
  options = {};
  options.adapt.clear();
  EXPECT_FALSE(options.Check(&why));
  options = {};
  options.max_training_seconds = -1;
  EXPECT_FALSE(options.Check(&why));
  EXPECT_NE(why.find("max_training_seconds"), std::string::npos);
}

}  // namespace
}  // namespace jgpm
