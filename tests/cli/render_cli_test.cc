// `jgpm render` end to end: a short clip from a real trial, and every kind of bad request
// refused on one line with nothing written.
#include <algorithm>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "io/json_file.h"
#include "test_support.h"

namespace jgpm {
namespace {

namespace fs = std::filesystem;

using Result = test::CommandResult;
Result Jgpm(const std::string& arguments) { return test::RunJgpm(arguments); }

std::string Amc() { return (test::CmuRoot() / "subjects/35/35_12.amc").string(); }

TEST(RenderCli, RendersAShortClipWithTheDefaultRig) {
  test::TempDir dir;
  const fs::path out = dir.path() / "clip";
  const Result r = Jgpm("render --amc " + Amc() + " --out " + out.string() +
                        " --max-frames 6 --cameras 2 --clutter 2 --drop-rate 0.2 --seed 3");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("rendered 6 frames"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("cam1: f "), std::string::npos) << r.out;
  EXPECT_EQ(r.err, "");  // a job this short shows no progress in a log
  const nlohmann::json truth = ReadJsonFile(out / "ground_truth.json", "truth");
  EXPECT_EQ(truth["frames"].size(), 6u);
  EXPECT_EQ(truth["degradations"]["clutter_blobs"], 2);
  EXPECT_NE(truth["source"]["asf"].get<std::string>().find("35.asf"), std::string::npos);
  for (const char* file : {"cam0.yaml", "cam1.yaml", "cam0.avi", "cam1.avi", "contact_sheet.png"})
    EXPECT_TRUE(fs::exists(out / file)) << file;
}

TEST(RenderCli, BadRequestsGiveOneLineAndWriteNothing) {
  test::TempDir dir;
  const std::string out = (dir.path() / "clip").string();
  dir.Write("unplaced.yaml",
            "%YAML:1.0\n---\nimage_width: 320\nimage_height: 240\n"
            "camera_matrix: !!opencv-matrix\n   rows: 3\n   cols: 3\n   dt: d\n   data: [ 300., 0., 160., 0., 300., 120., 0., 0., 1. ]\n"
            "distortion_coefficients: !!opencv-matrix\n   rows: 1\n   cols: 5\n   dt: d\n   data: [ 0., 0., 0., 0., 0. ]\n");
  fs::create_directories(dir.path() / "full");
  dir.Write("full/x.txt", "mine");
  const std::string unplaced = (dir.path() / "unplaced.yaml").string();
  struct Case {
    std::string arguments;
    std::string expected;
  };
  const std::vector<Case> cases = {
      {"--amc " + Amc() + " --out " + out + " --cameras 5", "--cameras"},
      {"--amc " + Amc() + " --out " + out + " --camera " + unplaced + " --cameras 2", "excludes"},
      {"--amc " + Amc() + " --out " + out + " --camera " + unplaced, "place the camera"},
      {"--amc " + Amc() + " --out " + out + " --fps 500", "exceeds the motion's 120"},
      {"--amc " + Amc() + " --out " + out + " --drop-rate 1.5", "--drop-rate"},
      {"--amc " + Amc() + " --out " + (dir.path() / "full").string(), "not empty"},
      {"--amc " + (dir.path() / "none.amc").string() + " --out " + out, "none.amc"},
      {"--amc " + Amc(), "--out"},
  };
  for (const Case& c : cases) {
    const Result r = Jgpm("render " + c.arguments);
    EXPECT_NE(r.status, 0) << c.arguments;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << c.arguments << "\n" << r.err;
    EXPECT_NE(r.err.find(c.expected), std::string::npos) << c.arguments << "\n" << r.err;
    EXPECT_FALSE(fs::exists(out)) << c.arguments;
    EXPECT_FALSE(fs::exists(out + ".partial")) << c.arguments;
  }
  EXPECT_TRUE(fs::exists(dir.path() / "full/x.txt"));
}

// Every clip of the tracking benchmark names a test-split trial (never training data) and
// options `jgpm render` accepts.
TEST(RenderCli, TrackingSuiteDefinitionRenders) {
  const std::vector<TrialId> test_split = test::SplitTrials("test");
  const std::vector<TrialId> train_split = test::SplitTrials("train");
  auto contains = [](const std::vector<TrialId>& ids, const std::string& name) {
    return std::any_of(ids.begin(), ids.end(), [&](const TrialId& id) { return id.name == name; });
  };
  std::ifstream suite(fs::path(JGPM_SOURCE_DIR) / "datasets_scripts/tracking_suite.txt");
  ASSERT_TRUE(suite.good());
  test::TempDir dir;
  int clips = 0;
  for (std::string line; std::getline(suite, line);) {
    std::istringstream words(line);
    std::string name, trial, options, word;
    if (!(words >> name) || name[0] == '#') continue;
    ASSERT_TRUE(static_cast<bool>(words >> trial)) << line;
    while (words >> word) options += " " + word;
    EXPECT_TRUE(contains(test_split, trial)) << trial;
    EXPECT_FALSE(contains(train_split, trial)) << trial;
    const fs::path amc = test::CmuRoot() / "subjects" / trial.substr(0, 2) / (trial + ".amc");
    const Result r = Jgpm("render --amc " + amc.string() + " --out " + (dir.path() / name).string() +
                          options + " --max-frames 2 --no-contact-sheet");
    EXPECT_EQ(r.status, 0) << line << "\n" << r.err;
    ++clips;
  }
  EXPECT_GE(clips, 4);
}

}  // namespace
}  // namespace jgpm
