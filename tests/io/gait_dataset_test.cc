#include "io/gait_dataset.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "io/text_reader.h"
#include "test_support.h"

namespace jgpm {
namespace {

using test::ExpectInputError;

std::vector<TrialId> Ids(std::initializer_list<const char*> names) {
  std::vector<TrialId> ids;
  for (const char* name : names) {
    TrialId id;
    EXPECT_TRUE(ParseTrialId(name, &id));
    ids.push_back(id);
  }
  return ids;
}

class GaitDatasetTest : public testing::Test {
 protected:
  static void SetUpTestSuite() {
    dataset_ = new GaitDataset(PrepareGaitDataset(test::CmuRoot(), "mini", Ids({"35_01", "39_01", "07_05"}), {}));
  }
  static void TearDownTestSuite() { delete dataset_; }
  static GaitDataset* dataset_;
};
GaitDataset* GaitDatasetTest::dataset_ = nullptr;

TEST_F(GaitDatasetTest, PreparesEachTrial) {
  const GaitDataset& d = *dataset_;
  ASSERT_EQ(d.trials.size(), 3u);
  EXPECT_EQ(d.channel_names.size(), 43u);
  EXPECT_EQ(d.joint_names.size(), 18u);
  EXPECT_EQ(d.trials[0].asf, "subjects/35/35.asf");
  EXPECT_EQ(d.trials[0].frames, 358);
  EXPECT_TRUE(d.trials[0].cycle.clean);
  EXPECT_EQ(d.trials[0].cycle.poses.rows(), 30);
  EXPECT_FALSE(d.trials[2].cycle.clean);  // 07_05: the slow walk's arms do not close the cycle
  EXPECT_EQ(d.NumClean(), 2);
  const std::string table = FormatGaitDatasetTable(d);
  EXPECT_NE(table.find("FLAGGED"), std::string::npos) << table;
  EXPECT_NE(table.find("3 trials, 2 clean cycles, 1 flagged"), std::string::npos) << table;
}

TEST_F(GaitDatasetTest, JsonRoundTripIsExact) {
  test::TempDir dir;
  WriteGaitDataset(dir.path() / "d.json", *dataset_);
  const GaitDataset back = ReadGaitDataset(dir.path() / "d.json");
  ASSERT_EQ(back.trials.size(), dataset_->trials.size());
  EXPECT_EQ(back.channel_names, dataset_->channel_names);
  EXPECT_EQ(back.options.poses_per_cycle, 30);
  for (size_t i = 0; i < back.trials.size(); ++i) {
    const GaitCycle& a = dataset_->trials[i].cycle;
    const GaitCycle& b = back.trials[i].cycle;
    EXPECT_EQ(back.trials[i].id.name, dataset_->trials[i].id.name);
    EXPECT_EQ(b.clean, a.clean);
    EXPECT_EQ(b.problem, a.problem);
    EXPECT_EQ(b.start_frame, a.start_frame);
    EXPECT_EQ(b.end_frame, a.end_frame);
    EXPECT_EQ(b.poses, a.poses);  // bit-identical doubles
  }
}

class GaitDatasetJsonErrors : public GaitDatasetTest {
 protected:
  // Writes the dataset with `edit` applied to its JSON and expects `parts` in the error.
  void Expect(const std::function<void(nlohmann::json&)>& edit, std::initializer_list<std::string> parts) {
    nlohmann::json j = nlohmann::json::parse(FormatGaitDatasetJson(*dataset_));
    edit(j);
    const auto path = dir_.Write("bad.json", j.dump());
    ExpectInputError([&] { ReadGaitDataset(path); }, parts);
  }
  test::TempDir dir_;
};

TEST_F(GaitDatasetJsonErrors, OtherVersion) {
  Expect([](nlohmann::json& j) { j["version"] = 2; }, {"bad.json", "version 2 is not supported (expected 1)"});
}
TEST_F(GaitDatasetJsonErrors, OtherFormat) {
  Expect([](nlohmann::json& j) { j["format"] = "model"; }, {"bad.json", "not a jgpm gait dataset"});
}
TEST_F(GaitDatasetJsonErrors, MissingField) {
  Expect([](nlohmann::json& j) { j["trials"][1]["cycle"].erase("start_frame"); },
         {"bad.json", "'trials[1].cycle.start_frame' missing"});
}
TEST_F(GaitDatasetJsonErrors, WrongType) {
  Expect([](nlohmann::json& j) { j["trials"][0]["frames"] = "many"; }, {"'trials[0].frames' has the wrong type"});
}
TEST_F(GaitDatasetJsonErrors, WrongPoseCount) {
  Expect([](nlohmann::json& j) { j["trials"][0]["poses"].erase(0); }, {"'trials[0].poses' expected 30 poses, found 29"});
}
TEST_F(GaitDatasetJsonErrors, WrongChannelCount) {
  Expect([](nlohmann::json& j) { j["trials"][0]["poses"][4].erase(0); }, {"'trials[0].poses[4]' expected 43 values, found 42"});
}
TEST_F(GaitDatasetJsonErrors, NullInsteadOfNumber) {
  // JSON has no NaN: writers emit null for it.
  Expect([](nlohmann::json& j) { j["trials"][0]["cycle"]["closure_deg"] = nullptr; }, {"'trials[0].cycle.closure_deg'"});
}
TEST_F(GaitDatasetJsonErrors, BadOptions) {
  Expect([](nlohmann::json& j) { j["options"]["max_cycle_s"] = 0.1; }, {"'options'", "min_cycle_s"});
}

TEST_F(GaitDatasetJsonErrors, TruncatedFile) {
  const std::string text = FormatGaitDatasetJson(*dataset_);
  const auto path = dir_.Write("cut.json", text.substr(0, text.size() / 2));
  ExpectInputError([&] { ReadGaitDataset(path); }, {"cut.json", "invalid JSON", "line"});
}

TEST(GaitDataset, MissingTrialFileNamesIt) {
  ExpectInputError([] { PrepareGaitDataset(test::CmuRoot(), "x", Ids({"35_99"}), {}); },
                   {"35_99.amc", "no such file"});
}

}  // namespace
}  // namespace jgpm
