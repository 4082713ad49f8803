#include "io/gait/split.h"

#include <set>

#include <gtest/gtest.h>

#include "test_support.h"

namespace jgpm {
namespace {

using test::ExpectInputError;

std::set<std::string> Names(const std::vector<TrialId>& ids) {
  std::set<std::string> names;
  for (const TrialId& id : ids) names.insert(id.name);
  return names;
}

TEST(Split, ParseTrialId) {
  TrialId id;
  ASSERT_TRUE(ParseTrialId("35_01", &id));
  EXPECT_EQ(id.subject, "35");
  EXPECT_EQ(id.name, "35_01");
  ASSERT_TRUE(ParseTrialId("64_golf01", &id));
  EXPECT_EQ(id.subject, "64");
  for (const char* bad : {"", "35", "_01", "35_", "a5_01", "35_0-1", "35 01", "../35_01"}) {
    EXPECT_FALSE(ParseTrialId(bad, &id)) << bad;
  }
}

TEST(Split, ReadsIdsCommentsAndBlankLines) {
  test::TempDir dir;
  const auto ids = ReadSplit(dir.Write("s.txt", "# header\n35_01\n\n  39_02  # note\n"));
  ASSERT_EQ(ids.size(), 2u);
  EXPECT_EQ(ids[1].name, "39_02");
}

TEST(Split, Errors) {
  test::TempDir dir;
  ExpectInputError([&] { ReadSplit(dir.Write("a.txt", "35_01\nwalk\n")); }, {"a.txt:2", "trial id such as 35_01", "'walk'"});
  ExpectInputError([&] { ReadSplit(dir.Write("b.txt", "35_01\n35_01\n")); }, {"b.txt:2", "listed twice"});
  ExpectInputError([&] { ReadSplit(dir.Write("c.txt", "35_01 35_02\n")); }, {"c.txt:1", "one trial id per line"});
  ExpectInputError([&] { ReadSplit(dir.Write("d.txt", "# nothing\n")); }, {"d.txt", "lists no trials"});
  ExpectInputError([&] { ResolveSplitPath("nosuch", JGPM_SPLITS_DIR); }, {"--split nosuch", "train", "test"});
}

TEST(Split, ParsesFromMemoryNamingTheSource) {
  const auto ids = ParseSplit("35_01\r\n\t07_12\t# tabs and CRLF\n", "memory");
  ASSERT_EQ(ids.size(), 2u);
  EXPECT_EQ(ids[1].subject, "07");
  ExpectInputError([] { ParseSplit("35_01\n35_0.1\n", "memory"); }, {"memory:2", "'35_0.1'"});
  ExpectInputError([] { ParseSplit("", "memory"); }, {"memory", "lists no trials"});
}

// The split fuzzer's seed (tests/fuzz/seeds/split) is a valid split.
TEST(Split, FuzzSeedIsValid) {
  const auto ids = ReadSplit(std::string(JGPM_SOURCE_DIR) + "/tests/fuzz/seeds/split/small.txt");
  EXPECT_EQ(Names(ids), (std::set<std::string>{"35_01", "39_02", "64_golf01", "07_12"}));
}

TEST(Split, NamedSplitsResolve) {
  EXPECT_EQ(ResolveSplitPath("train", JGPM_SPLITS_DIR).filename(), "train.txt");
  test::TempDir dir;
  const auto file = dir.Write("mine.txt", "35_01\n");
  EXPECT_EQ(ResolveSplitPath(file.string(), JGPM_SPLITS_DIR), file);
}

// The default splits as the issue defines them, checked against the data that exists.
TEST(Split, DefaultSplitsMatchTheirDefinition) {
  const auto train = Names(test::SplitTrials("train"));
  const auto test_set = Names(test::SplitTrials("test"));
  const auto walking = Names(test::SplitTrials("walking"));
  EXPECT_EQ(train.size(), 20u);
  std::set<std::string> subjects;
  for (const auto& name : train) subjects.insert(name.substr(0, name.find('_')));
  EXPECT_EQ(subjects, (std::set<std::string>{"02", "05", "35", "39"}));
  // Test = subject 07 and the 35/39 walking trials not used for training.
  std::set<std::string> expected_test;
  for (const auto& name : walking) {
    const std::string subject = name.substr(0, name.find('_'));
    if (subject == "07" || ((subject == "35" || subject == "39") && !train.count(name))) {
      expected_test.insert(name);
    }
  }
  EXPECT_EQ(test_set, expected_test);
  for (const auto& name : train) EXPECT_TRUE(walking.count(name)) << name;
  for (const auto& ids : {test::SplitTrials("walking")}) {
    for (const TrialId& id : ids) {
      EXPECT_TRUE(std::filesystem::is_regular_file(TrialAmcPath(test::CmuRoot(), id))) << id.name;
      EXPECT_TRUE(std::filesystem::is_regular_file(TrialAsfPath(test::CmuRoot(), id))) << id.name;
    }
  }
}

}  // namespace
}  // namespace jgpm
