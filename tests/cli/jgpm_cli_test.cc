// The `jgpm` command end to end: exit codes, one-line errors naming file:line, and the
// data subcommands on real trials.
#include <fstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "io/text_reader.h"
#include "test_support.h"

namespace jgpm {
namespace {

namespace fs = std::filesystem;

using Result = test::CommandResult;
Result Jgpm(const std::string& arguments) { return test::RunJgpm(arguments); }

int Lines(const std::string& text) { return static_cast<int>(std::count(text.begin(), text.end(), '\n')); }

TEST(JgpmCli, HelpOnEverySubcommand) {
  for (const char* command : {"", "data", "data info", "data convert", "data cycles", "train", "plot", "plot latent", "eval", "synth", "render"}) {
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

class JgpmCliBadFile : public testing::TestWithParam<BadFile> {};

TEST_P(JgpmCliBadFile, OneLineNamingFileAndLine) {
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
    EXPECT_EQ(Lines(r.err), 1) << r.err;
    EXPECT_NE(r.err.find(file.string() + ":" + c.expected), std::string::npos)
        << r.err << "lacks " << file.string() << ":" << c.expected;
    EXPECT_FALSE(fs::exists(out));
  }
}

INSTANTIATE_TEST_SUITE_P(
    Cases, JgpmCliBadFile,
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

TEST(JgpmCli, MissingFilesAndDirectories) {
  test::TempDir dir;
  Result r = Jgpm("data info " + (dir.path() / "none.bvh").string());
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("none.bvh: no such file"), std::string::npos) << r.err;
  r = Jgpm("data info " + dir.path().string());
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find(dir.path().string() + ": is a directory"), std::string::npos) << r.err;
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

// `jgpm train` for every model kind on the default split (few iterations: the point is
// the command, the file and its reload), then `jgpm plot latent` on one of them.
TEST(JgpmCli, TrainEveryKindAndPlot) {
  test::TempDir dir;
  for (const char* kind : {"pca", "gplvm", "gpdm", "bgpdm", "llgpdm", "jgpm", "mljgpm-torus", "mljgpm-cyl"}) {
    const fs::path model = dir.path() / (std::string(kind) + ".json");
    const Result r = Jgpm(std::string("train --model ") + kind + " --max-iterations 3 --data " +
                          test::CmuRoot().string() + " --out " + model.string());
    ASSERT_EQ(r.status, 0) << kind << "\n" << r.err;
    EXPECT_NE(r.out.find("wrote " + model.string()), std::string::npos) << r.out;
    const nlohmann::json j = nlohmann::json::parse(ReadTextFile(model, "json"));
    EXPECT_EQ(j["model"]["kind"], kind);
    const size_t expected = std::string(kind).rfind("mljgpm", 0) == 0 ? 1800 : 600;
    EXPECT_EQ(j["model"]["latent"].size(), expected) << kind;
  }
  const fs::path png = dir.path() / "latent.png";
  const Result r = Jgpm("plot latent " + (dir.path() / "mljgpm-torus.json").string() + " --out " + png.string());
  ASSERT_EQ(r.status, 0) << r.err;
  std::ifstream in(png, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(bytes.substr(1, 3), "PNG");
  EXPECT_GT(bytes.size(), 10000u);
}

// A time budget ends (local) learning early and the model is still written, saying so.
TEST(JgpmCli, TrainStopsAtTheTimeBudgetAndWritesTheModel) {
  test::TempDir dir;
  const fs::path model = dir.path() / "m.json";
  const Result r = Jgpm("train --model mljgpm-cyl --learning local --neighbourhood 60 --max-time 0.5 --data " +
                        test::CmuRoot().string() + " --out " + model.string());
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("local learning: stopped (time budget of 0.5 s used up)"), std::string::npos) << r.out;
  const nlohmann::json j = nlohmann::json::parse(ReadTextFile(model, "json"));
  EXPECT_EQ(j["model"]["summary"]["termination"], "stopped");
  EXPECT_LT(j["model"]["summary"]["wall_seconds"].get<double>(), 5.0);
}

TEST(JgpmCli, TrainAndPlotBadInput) {
  test::TempDir dir;
  Result r = Jgpm("train --model svm --out " + (dir.path() / "m.json").string());
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("--model svm: expected one of pca, gplvm"), std::string::npos) << r.err;
  r = Jgpm("train --learning sideways --out x.json");
  EXPECT_EQ(r.status, 2);
  for (const char* option : {"--neighbourhood 2", "--max-time -1", "--threads -1"}) {
    r = Jgpm(std::string("train ") + option + " --out x.json");
    EXPECT_EQ(r.status, 2) << option;
    EXPECT_NE(r.err.find(std::string(option).substr(0, std::string(option).find(' '))), std::string::npos) << r.err;
  }
  const fs::path bad = dir.Write("bad.json", "{\"format\": \"jgpm-model\", \"version\": 99}");
  r = Jgpm("plot latent " + bad.string() + " --out " + (dir.path() / "p.png").string());
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("version 99 is not supported"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir.path() / "p.png"));
  EXPECT_FALSE(fs::exists(dir.path() / "m.json"));
}

// `jgpm eval`: one case to JSON, the paper suite on two trials to CSV and charts.
TEST(JgpmCli, EvalOneCaseAndTheSuite) {
  test::TempDir dir;
  const std::string data = " --data " + test::CmuRoot().string();
  const fs::path pca = dir.path() / "pca.json", gplvm = dir.path() / "gplvm.json";
  ASSERT_EQ(Jgpm("train --model pca" + data + " --out " + pca.string()).status, 0);
  ASSERT_EQ(Jgpm("train --model gplvm --max-iterations 3" + data + " --out " + gplvm.string()).status, 0);
  const fs::path trials = dir.Write("two.txt", "07_01\n35_10\n");

  const fs::path json = dir.path() / "filtering.json";
  Result r = Jgpm("eval --model " + pca.string() + " --task filtering --noise 0.1 --draws 2 --scale 0.5 --trials " +
                  trials.string() + data + " --json " + json.string());
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(ReadTextFile(json, "json"));
  ASSERT_EQ(j["trials"].size(), 2u);
  EXPECT_EQ(j["trials"][0]["trial"], "07_01");
  EXPECT_NEAR(j["mean_error_mm"].get<double>(),
              (j["trials"][0]["error_mm"].get<double>() + j["trials"][1]["error_mm"].get<double>()) / 2, 1e-9);
  EXPECT_EQ(j["draw_errors_mm"].size(), 2u);
  EXPECT_EQ(j["case"], "filtering 10% s=0.5");
  EXPECT_NE(r.out.find("filtering 10% s=0.5"), std::string::npos) << r.out;

  const fs::path out = dir.path() / "suite";
  r = Jgpm("eval --suite paper --model " + pca.string() + " --model " + gplvm.string() + " --trials " +
           trials.string() + data + " --out " + out.string());
  ASSERT_EQ(r.status, 0) << r.err;
  const std::string csv = ReadTextFile(out / "paper.csv", "csv");
  EXPECT_EQ(Lines(csv), 1 + 2 * 35);
  EXPECT_NE(csv.find("gplvm,reconstruction,left-side,0,0.667,"), std::string::npos) << csv;
  for (const char* png : {"interpolation.png", "reconstruction.png", "filtering.png"}) {
    EXPECT_GT(fs::file_size(out / png), 5000u) << png;
  }
}

TEST(JgpmCli, EvalBadInput) {
  test::TempDir dir;
  const fs::path json = dir.path() / "e.json";
  const fs::path pca = dir.path() / "pca.json";
  ASSERT_EQ(Jgpm("train --model pca --data " + test::CmuRoot().string() + " --out " + pca.string()).status, 0);
  const struct {
    std::string arguments;
    int status;
    std::string message;
  } cases[] = {
      {"--task reconstruction", 1, "--task reconstruction: missing joints go with reconstruction"},
      {"--task filtering", 1, "--task filtering: filtering needs a noise level > 0"},
      {"--task interpolation --missing left-arm", 1, "missing joints go with reconstruction"},
      {"--task sideways", 2, "--task"},
      {"--task filtering --noise -1", 2, "--noise"},
      {"--suite paper", 1, "--suite paper: needs --out DIR"},
      {"", 1, "give --task"},
      {"--task interpolation --trials nosuchsplit", 1, "nosuchsplit"},
  };
  for (const auto& c : cases) {
    const Result r = Jgpm("eval --model " + pca.string() + " " + c.arguments + " --data " + test::CmuRoot().string() +
                          " --json " + json.string());
    EXPECT_EQ(r.status, c.status) << c.arguments << "\n" << r.err;
    EXPECT_NE(r.err.find(c.message), std::string::npos) << c.arguments << "\n" << r.err;
    EXPECT_EQ(Lines(r.err), 1) << r.err;
  }
  const Result r = Jgpm("eval --model " + (dir.path() / "none.json").string() + " --task interpolation --json " + json.string());
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("none.json"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(json));
}

TEST(JgpmCli, SynthWritesMotionAnAnimationToolLoads) {
  test::TempDir dir;
  const std::string data = " --data " + test::CmuRoot().string();
  const fs::path jgpm = dir.path() / "jgpm.json", pca = dir.path() / "pca.json";
  ASSERT_EQ(Jgpm("train --model jgpm --max-iterations 3" + data + " --out " + jgpm.string()).status, 0);
  ASSERT_EQ(Jgpm("train --model pca" + data + " --out " + pca.string()).status, 0);
  const fs::path amc = dir.path() / "walk.amc", png = dir.path() / "walk.png";
  Result r = Jgpm("synth --model " + jgpm.string() + " --path inner-spiral --frames 40 --out " + amc.string() +
                  " --png " + png.string());
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(fs::exists(dir.path() / "walk.asf"));
  EXPECT_TRUE(fs::exists(png));
  r = Jgpm("data info " + amc.string() + " --fps 30");  // finds walk.asf beside it
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("frames 40"), std::string::npos) << r.out;

  r = Jgpm("synth --model " + pca.string() + " --out " + amc.string());
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("manifold"), std::string::npos) << r.err;
  r = Jgpm("synth --model " + jgpm.string() + " --out " + (dir.path() / "w.fbx").string());
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find(".amc or .bvh"), std::string::npos) << r.err;
  r = Jgpm("synth --model " + jgpm.string() + " --path zigzag --out " + amc.string());
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("--path"), std::string::npos) << r.err;
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
