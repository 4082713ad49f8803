// The `jgpm` command end to end: exit codes, one-line errors naming file:line, and the
// data subcommands on real trials.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "io/text_reader.h"
#include "test_support.h"

namespace jgpm {
namespace {

namespace fs = std::filesystem;

struct Result {
  int status;
  std::string out;
  std::string err;
};

Result Jgpm(const std::string& arguments) {
  Result r;
  r.status = test::RunCommand(std::string(JGPM_BINARY) + " " + arguments, &r.out, &r.err);
  return r;
}

int Lines(const std::string& text) { return static_cast<int>(std::count(text.begin(), text.end(), '\n')); }

TEST(JgpmCli, HelpOnEverySubcommand) {
  for (const char* command : {"", "data", "data info", "data convert", "data cycles"}) {
    const Result r = Jgpm(std::string(command) + " --help");
    EXPECT_EQ(r.status, 0) << command << r.err;
    EXPECT_NE(r.out.find("Usage"), std::string::npos) << command;
  }
}

TEST(JgpmCli, BadOptionsGiveOneLineAndExit2) {
  for (const char* arguments : {"", "bogus", "data info", "data info x.amc --fps -3",
                                "data convert a.amc", "data cycles --out x.json --poses 1",
                                "data info x.bvh --bvh-unit furlong"}) {
    const Result r = Jgpm(arguments);
    EXPECT_EQ(r.status, 2) << arguments << "\n" << r.err;
    EXPECT_EQ(Lines(r.err), 1) << arguments << "\n" << r.err;
    EXPECT_NE(r.err.find("jgpm: error:"), std::string::npos) << r.err;
  }
}

// Malformed files: one line on stderr naming file:line, exit 1, for each parser.
TEST(JgpmCli, MalformedFilesNameTheFileAndLine) {
  test::TempDir dir;
  const fs::path asf = dir.Write("s_01.asf", test::Replace(test::SmallAsfText(), "length 4", "length x"));
  const fs::path good_asf = dir.Write("s.asf", test::SmallAsfText());
  const fs::path amc = dir.Write("s_01.amc", ":FULLY-SPECIFIED\n:DEGREES\n1\nroot 0 0 0 0 0 0\nthigh 1\n");
  const fs::path bvh = dir.Write("b.bvh", "HIERARCHY\nROOT r\n{\nOFFSET 0 0\n}\n");
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"data info " + asf.string(), asf.string() + ":" + std::to_string(test::LineOf(test::SmallAsfText(), "length 4"))},
      {"data info " + amc.string(), amc.string() + ":5"},
      {"data info " + bvh.string(), bvh.string() + ":5"},
      {"data info " + dir.path().string() + "/none.bvh", "no such file"},
      {"data info " + dir.path().string(), "is a directory"},
      {"data convert " + amc.string() + " --out " + (dir.path() / "o.bvh").string(), amc.string() + ":5"},
  };
  for (const auto& [arguments, expected] : cases) {
    const Result r = Jgpm(arguments);
    EXPECT_EQ(r.status, 1) << arguments;
    EXPECT_EQ(Lines(r.err), 1) << r.err;
    EXPECT_NE(r.err.find(expected), std::string::npos) << r.err << "lacks " << expected;
  }
  EXPECT_FALSE(fs::exists(dir.path() / "o.bvh"));
}

TEST(JgpmCli, InfoAndConvertOnACmuTrial) {
  const fs::path amc = test::CmuRoot() / "subjects/39/39_01.amc";
  Result r = Jgpm("data info " + amc.string());
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("frames 378"), std::string::npos) << r.out;
  test::TempDir dir;
  const fs::path bvh = dir.path() / "39_01.bvh";
  r = Jgpm("data convert " + amc.string() + " --out " + bvh.string());
  ASSERT_EQ(r.status, 0) << r.err;
  r = Jgpm("data info " + bvh.string());
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("frames 378"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("joints 31"), std::string::npos) << r.out;
  r = Jgpm("data convert " + bvh.string() + " --out " + (dir.path() / "back.amc").string() +
           " --asf " + (test::CmuRoot() / "subjects/39/39.asf").string());
  ASSERT_EQ(r.status, 0) << r.err;
  r = Jgpm("data convert " + bvh.string() + " --out " + bvh.string());
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("is the input"), std::string::npos) << r.err;
}

TEST(JgpmCli, CyclesOnTheDefaultSplit) {
  test::TempDir dir;
  const fs::path out = dir.path() / "train.json";
  const Result r = Jgpm("data cycles --split train --data " + test::CmuRoot().string() + " --out " + out.string());
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("20 trials, 20 clean cycles, 0 flagged"), std::string::npos) << r.out;
  const nlohmann::json j = nlohmann::json::parse(ReadTextFile(out, "json"));
  ASSERT_EQ(j["trials"].size(), 20u);
  for (const auto& trial : j["trials"]) {
    EXPECT_TRUE(trial["clean"].get<bool>()) << trial["id"];
    EXPECT_EQ(trial["poses"].size(), 30u);
    EXPECT_GT(trial["cycle"]["end_frame"].get<int>(), trial["cycle"]["start_frame"].get<int>());
  }
}

TEST(JgpmCli, CyclesWithoutDataListsThePlacesTried) {
  test::TempDir dir;
  const Result r = Jgpm("data cycles --data " + dir.path().string() + " --out " + (dir.path() / "x.json").string());
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("--data " + dir.path().string()), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir.path() / "x.json"));
}

}  // namespace
}  // namespace jgpm
