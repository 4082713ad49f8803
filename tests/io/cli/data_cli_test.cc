// `jgpm data`: one-line errors naming file:line for each kind of bad motion file, missing
// files, info and conversion on a CMU trial, gait cycles of the default split.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "io/base/text_reader.h"
#include "test_support.h"

namespace jgpm {
namespace {

namespace fs = std::filesystem;

using Result = test::CommandResult;
Result Jgpm(const std::string& arguments) { return test::RunJgpm(arguments); }

// Each kind of bad input the issue lists, through the command: exit 1, one line on stderr
// naming file:line and what was expected, and no output file.
struct BadFile {
  std::string name;
  std::string file;      // written into a temporary folder with the small skeleton s.asf
  std::string content;
  std::string expected;  // after "<folder>/<file>:"
};
void PrintTo(const BadFile& c, std::ostream* os) { *os << c.name; }

const char kAmcHeader[] = ":FULLY-SPECIFIED\n:DEGREES\n";
const char kBvhHead[] = "HIERARCHY\nROOT r\n{\n  OFFSET 0 0 0\n  CHANNELS 1 Xrotation\n}\nMOTION\nFrames: 2\nFrame Time: 0.1\n";

class DataCliBadFile : public testing::TestWithParam<BadFile> {};

TEST_P(DataCliBadFile, OneLineNamingFileAndLine) {
  const BadFile& c = GetParam();
  test::TempDir dir;
  dir.Write("s.asf", test::SmallAsfText());
  const fs::path file = dir.Write(c.file, c.content);
  const fs::path out = dir.path() / (file.extension() == ".bvh" ? "out.amc" : "out.bvh");
  for (const std::string command : {"data info ", "data convert "}) {
    if (file.extension() == ".asf" && command == "data convert ") continue;
    std::string arguments = command + file.string();
    if (file.extension() != ".asf") arguments += " --asf " + (dir.path() / "s.asf").string();
    if (command == "data convert ") arguments += " --out " + out.string();
    const Result r = Jgpm(arguments);
    EXPECT_EQ(r.status, 1) << arguments;
    EXPECT_EQ(test::CountLines(r.err), 1) << r.err;
    EXPECT_NE(r.err.find(file.string() + ":" + c.expected), std::string::npos)
        << r.err << "lacks " << file.string() << ":" << c.expected;
    EXPECT_FALSE(fs::exists(out));
  }
}

INSTANTIATE_TEST_SUITE_P(
    Cases, DataCliBadFile,
    testing::Values(
        BadFile{"AsfTruncated", "t.asf", std::string(test::SmallAsfText()).substr(0, std::string(test::SmallAsfText()).find("    limits (-10.0")),
                std::to_string(test::LineOf(test::SmallAsfText(), "id 3") - 1) + ": file ends inside a bone block"},
        BadFile{"AsfNan", "n.asf", test::Replace(test::SmallAsfText(), "length 4", "length nan"),
                std::to_string(test::LineOf(test::SmallAsfText(), "length 4")) + ": expected a finite number for length"},
        BadFile{"AsfEmpty", "e.asf", "", "1: file is empty"},
        BadFile{"AmcTruncated", "t.amc", std::string(kAmcHeader) + "1\nroot 0 0 0 0 0 0\nthigh 1 2\n", "5: file ends inside frame 1"},
        BadFile{"AmcWrongCount", "w.amc", std::string(kAmcHeader) + "1\nroot 0 0 0 0 0\n", "4: expected 6 value(s) for bone 'root'"},
        BadFile{"AmcUnknownBone", "u.amc", std::string(kAmcHeader) + "1\nlowerback 0 0 0\n", "4: unknown bone 'lowerback'"},
        BadFile{"AmcNan", "n.amc", std::string(kAmcHeader) + "1\nroot 0 0 nan 0 0 0\n", "4: expected a finite number for root.tz"},
        BadFile{"AmcInf", "i.amc", std::string(kAmcHeader) + "1\nroot 0 0 0 0 -inf 0\n", "4: expected a finite number for root.ry"},
        BadFile{"AmcMissingDegrees", "d.amc", ":FULLY-SPECIFIED\n1\n", "2: expected :DEGREES"},
        BadFile{"AmcMissingFullySpecified", "f.amc", ":DEGREES\n1\n", "2: expected :FULLY-SPECIFIED"},
        BadFile{"AmcOfAnotherSkeleton", "o.amc", std::string(kAmcHeader) + "1\nroot 0 0 0 0 0 0\nthigh 1 2\nshin 3 4\n", "6: expected 1 value(s) for bone 'shin'"},
        BadFile{"AmcEmpty", "e.amc", "\n", "1: file is empty"},
        BadFile{"BvhBadHierarchy", "h.bvh", test::Replace(kBvhHead, "}\nMOTION", "MOTION"), "6: expected '}' to close the hierarchy"},
        BadFile{"BvhTruncated", "t.bvh", std::string(kBvhHead) + "1\n", "10: file ends after 1 of 2 frames"},
        BadFile{"BvhWrongCount", "w.bvh", std::string(kBvhHead) + "1\n1 2\n", "11: expected 1 channel values in frame 2, found 2"},
        BadFile{"BvhEmpty", "e.bvh", " ", "1: file is empty"}),
    [](const testing::TestParamInfo<BadFile>& info) { return info.param.name; });

TEST(DataCli, MissingFilesAndDirectories) {
  test::TempDir dir;
  Result r = Jgpm("data info " + (dir.path() / "none.bvh").string());
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("none.bvh: no such file"), std::string::npos) << r.err;
  r = Jgpm("data info " + dir.path().string());
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find(dir.path().string() + ": is a directory"), std::string::npos) << r.err;
}

TEST(DataCli, InfoAndConvertOnACmuTrial) {
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

TEST(DataCli, CyclesOnTheDefaultSplit) {
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

TEST(DataCli, CyclesWithoutDataListsThePlacesTried) {
  test::TempDir dir;
  const Result r = Jgpm("data cycles --data " + dir.path().string() + " --out " + (dir.path() / "x.json").string());
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("--data " + dir.path().string()), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir.path() / "x.json"));
}

}  // namespace
}  // namespace jgpm
