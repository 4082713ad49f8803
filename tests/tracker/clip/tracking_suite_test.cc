// The tracking suite's file format: the shipped suite parses to the clips it lists, and
// each malformed line is refused naming the file, the line and what was expected.
#include "tracker/clip/tracking_suite.h"

#include <algorithm>
#include <set>
#include <utility>

#include <gtest/gtest.h>

#include "test_support.h"

namespace jgpm {
namespace {

const char kSuite[] =
    "# comment line\n"
    "a-4cam   07_01   --cameras 4\n"
    "\n"
    "b.deg    35_30   --cameras 2 --holes 3 --drop-rate 0.1 --seed 2   # trailing comment\n";

TEST(TrackingSuite, ParsesNamesTrialsAndOptions) {
  const std::vector<SuiteClip> clips = ParseTrackingSuite(kSuite, "s.txt");
  ASSERT_EQ(clips.size(), 2u);
  EXPECT_EQ(clips[0].name, "a-4cam");
  EXPECT_EQ(clips[0].trial.name, "07_01");
  EXPECT_EQ(clips[0].options.rig.num_cameras, 4);
  EXPECT_EQ(clips[1].trial.subject, "35");
  EXPECT_EQ(clips[1].options.rig.num_cameras, 2);
  EXPECT_EQ(clips[1].options.degradations.holes, 3);
  EXPECT_DOUBLE_EQ(clips[1].options.degradations.drop_rate, 0.1);
  EXPECT_EQ(clips[1].options.seed, 2u);
  EXPECT_EQ(clips[1].options_text, "--cameras 2 --holes 3 --drop-rate 0.1 --seed 2");
}

TEST(TrackingSuite, RealismOptionsAndFlags) {
  const std::vector<SuiteClip> clips = ParseTrackingSuite(
      "w 35_16 --rig webcam --body-seed 13 --clothing coat --bag --shadow --occluders 2 --calibration-error 1.5\n"
      "s 07_01 --rig surveillance --cameras 3 --shadow --pause 1,0.5 --pause 0.25,2\n"
      "g 07_03 --ring-height 1000 --reflection 0.3\n",
      "s.txt");
  ASSERT_EQ(clips.size(), 3u);
  EXPECT_EQ(clips[2].options.rig.camera_height_mm, 1000);
  EXPECT_EQ(clips[2].options.scene.reflection, 0.3);
  EXPECT_EQ(clips[0].options.rig.camera_height_mm, 1500);
  const ClipOptions& w = clips[0].options;
  EXPECT_EQ(w.rig.kind, RigKind::kWebcam);
  EXPECT_EQ(w.rig.num_cameras, 1);  // the webcam rig's own
  EXPECT_EQ(w.body.body_seed, 13u);
  EXPECT_EQ(w.body.clothing, Clothing::kCoat);
  EXPECT_TRUE(w.body.bag);
  EXPECT_TRUE(w.scene.shadow);
  EXPECT_EQ(w.scene.occluders, 2);
  EXPECT_DOUBLE_EQ(w.calibration_error, 1.5);
  EXPECT_TRUE(w.pauses.empty());
  ASSERT_EQ(clips[1].options.pauses.size(), 2u);
  EXPECT_EQ(clips[1].options.pauses[1].at_s, 0.25);
  EXPECT_EQ(clips[1].options.pauses[1].for_s, 2);
  EXPECT_EQ(clips[0].options_text,
            "--rig webcam --body-seed 13 --clothing coat --bag --shadow --occluders 2 --calibration-error 1.5");
  EXPECT_EQ(clips[1].options.rig.kind, RigKind::kSurveillance);
  EXPECT_EQ(clips[1].options.rig.num_cameras, 3);
  EXPECT_FALSE(clips[1].options.body.bag);
  EXPECT_TRUE(clips[1].options.scene.shadow);
  for (const auto& [text, phrase] : std::vector<std::pair<std::string, std::string>>{
           {"x 07_01 --rig blimp\n", "expected ring, surveillance or webcam"},
           {"x 07_01 --clothing cape\n", "expected none, trousers, coat or skirt"},
           {"x 07_01 --rig webcam --cameras 2\n", "one camera"},
           {"x 07_01 --occluders 9\n", "occluders"},
           {"x 07_01 --calibration-error -1\n", "calibration error"},
           {"x 07_01 --pause 1\n", "AT_S,FOR_S"},
           {"x 07_01 --pause 1,0\n", "AT_S,FOR_S"}}) {
    const std::string line = text;  // (clang 14 cannot capture a structured binding)
    test::ExpectInputError([&line] { ParseTrackingSuite(line, "s.txt"); }, {"s.txt:1", phrase});
  }
}

TEST(TrackingSuite, TheShippedSuitesParse) {
  for (const char* name : {"realism_suite.txt", "realism_tuning.txt", "glossy_suite.txt", "harsh_suite.txt"}) {
    const std::vector<SuiteClip> clips =
        ReadTrackingSuite(std::filesystem::path(JGPM_SOURCE_DIR) / "datasets_scripts" / name);
    EXPECT_GE(clips.size(), 5u) << name;
  }
  // The realism suite: every factor alone, and all at once, on trials that start and turn.
  const std::vector<SuiteClip> realism =
      ReadTrackingSuite(std::filesystem::path(JGPM_SOURCE_DIR) / "datasets_scripts/realism_suite.txt");
  bool body = false, clothing = false, shadow = false, occluders = false, calibration = false, rig = false,
       subject131 = false, stop = false, all = false;
  for (const SuiteClip& c : realism) {
    const ClipOptions& o = c.options;
    body |= o.body.body_seed > 0;
    clothing |= o.body.clothing != Clothing::kNone;
    shadow |= o.scene.shadow;
    occluders |= o.scene.occluders > 0;
    calibration |= o.calibration_error > 0;
    rig |= o.rig.kind != RigKind::kRing;
    subject131 |= c.trial.subject == "131";
    stop |= !o.pauses.empty();
    all |= o.body.body_seed > 0 && o.body.clothing != Clothing::kNone && o.scene.shadow && o.scene.occluders > 0 &&
           o.calibration_error > 0 && o.rig.kind != RigKind::kRing;
  }
  EXPECT_TRUE(body && clothing && shadow && occluders && calibration && rig && subject131 && stop && all);
}

// Several walkers: trials joined by '+', one --walk each.
TEST(TrackingSuite, SeveralWalkersWithTheirWalks) {
  const std::vector<SuiteClip> clips =
      ParseTrackingSuite("x 07_01+35_10+39_12 --walk 0,0,0,0 --walk 10,20,90,0.5 --walk -1,-2,180,-0.25\n", "s.txt");
  ASSERT_EQ(clips.size(), 1u);
  EXPECT_EQ(clips[0].trial.name, "07_01");
  ASSERT_EQ(clips[0].others.size(), 2u);
  EXPECT_EQ(clips[0].others[1].name, "39_12");
  ASSERT_EQ(clips[0].walks.size(), 3u);
  EXPECT_EQ(clips[0].walks[1].at_z_mm, 20);
  EXPECT_EQ(clips[0].walks[2].delay_s, -0.25);
  EXPECT_TRUE(clips[0].walks[2].placed);
  for (const auto& [text, phrase] : std::vector<std::pair<std::string, std::string>>{
           {"x 07_01+35_10 --walk 0,0,0,0\n", "one --walk per walker (2), found 1"},
           {"x 07_01+ --cameras 2\n", "several joined by '+'"},
           {"x 07_01 --walk 0,0,zero,0\n", "X_MM,Z_MM,HEADING_DEG,DELAY_S"},
           {"x 07_01+35_10 --walk 0,0,0,1 --walk 0,0,0,0\n", "first walker's --walk delay must be 0"},
           {"x 07_01+07_01+07_01+07_01+07_01+07_01+07_01+07_01+07_01\n", "at most 8 walkers"}}) {
    const std::string line = text;  // (clang 14 cannot capture a structured binding)
    test::ExpectInputError([&line] { ParseTrackingSuite(line, "s.txt"); }, {"s.txt:1", phrase});
  }
}

// The crowd suite: test-split trials only, 2, 3 and 5 walkers, each placed, a surveillance
// rig among them.
TEST(TrackingSuite, TheCrowdSuiteHasTwoThreeAndFiveWalkersOfTheTestSplit) {
  const std::vector<SuiteClip> clips =
      ReadTrackingSuite(std::filesystem::path(JGPM_SOURCE_DIR) / "datasets_scripts/crowd_suite.txt");
  const std::vector<TrialId> test_split = test::SplitTrials("test");
  std::set<size_t> walkers;
  bool surveillance = false;
  for (const SuiteClip& c : clips) {
    std::vector<TrialId> trials = {c.trial};
    trials.insert(trials.end(), c.others.begin(), c.others.end());
    for (const TrialId& t : trials) {
      EXPECT_TRUE(std::any_of(test_split.begin(), test_split.end(), [&](const TrialId& s) { return s.name == t.name; }))
          << c.name << ": " << t.name;
    }
    EXPECT_EQ(c.walks.size(), trials.size()) << c.name;
    walkers.insert(trials.size());
    surveillance |= c.options.rig.kind == RigKind::kSurveillance;
  }
  EXPECT_EQ(walkers, (std::set<size_t>{2, 3, 5}));
  EXPECT_TRUE(surveillance);
}

// The occluded crowd suite: each of the crowd suite's clips, the same walkers and walks
// and render options, with static occluders painted.
TEST(TrackingSuite, TheOccludedCrowdSuiteIsTheCrowdSuiteWithOccluders) {
  const std::filesystem::path dir = std::filesystem::path(JGPM_SOURCE_DIR) / "datasets_scripts";
  const std::vector<SuiteClip> crowd = ReadTrackingSuite(dir / "crowd_suite.txt");
  const std::vector<SuiteClip> occluded = ReadTrackingSuite(dir / "crowd_occluded_suite.txt");
  ASSERT_EQ(occluded.size(), crowd.size());
  for (size_t k = 0; k < crowd.size(); ++k) {
    EXPECT_EQ(occluded[k].name, crowd[k].name + "-occl");
    EXPECT_EQ(occluded[k].options_text, crowd[k].options_text + " --occluders 3") << occluded[k].name;
    EXPECT_EQ(occluded[k].options.scene.occluders, 3) << occluded[k].name;
    EXPECT_EQ(occluded[k].trial.name, crowd[k].trial.name);
    EXPECT_EQ(occluded[k].others.size(), crowd[k].others.size());
  }
}

TEST(TrackingSuite, TheShippedSuiteParses) {
  const std::vector<SuiteClip> clips =
      ReadTrackingSuite(std::filesystem::path(JGPM_SOURCE_DIR) / "datasets_scripts/tracking_suite.txt");
  ASSERT_GE(clips.size(), 4u);
  bool one_camera = false, four_cameras = false;
  for (const SuiteClip& clip : clips) {
    one_camera |= clip.options.rig.num_cameras == 1;
    four_cameras |= clip.options.rig.num_cameras == 4;
  }
  EXPECT_TRUE(one_camera && four_cameras);
}

class MalformedSuite : public testing::TestWithParam<test::MalformedCase> {};

TEST_P(MalformedSuite, NamesTheFileAndLine) {
  test::ExpectMalformed(GetParam(), kSuite, "s.txt", ParseTrackingSuite);
}

const test::MalformedCase kMalformed[] = {
    {"NoTrial", "a-4cam   07_01   --cameras 4", "a-4cam", "a-4cam", "expected NAME TRIAL"},
    {"BadTrial", "07_01   --cameras 4", "7-1 --cameras 4", "a-4cam", "expected a trial id"},
    {"SlashInName", "a-4cam ", "a/4cam ", "a/4cam", "may hold only letters"},
    {"DotFirst", "b.deg ", ".b ", ".b ", "may hold only letters"},
    {"NamedTwice", "b.deg ", "a-4cam ", "35_30", "named twice"},
    {"UnknownOption", "--holes 3", "--hole 3", "--hole", "unknown render option"},
    {"MissingValue", "--seed 2 ", "--seed ", "--seed", "needs a value"},
    {"NotANumber", "--cameras 4", "--cameras four", "four", "the value of --cameras"},
    {"OutOfRange", "--drop-rate 0.1", "--drop-rate 1.5", "--drop-rate", "drop"},
};
INSTANTIATE_TEST_SUITE_P(Cases, MalformedSuite, testing::ValuesIn(kMalformed), test::CaseName);

TEST(TrackingSuite, ASuiteWithoutClipsIsRefused) {
  test::ExpectInputError([] { ParseTrackingSuite("# nothing here\n\n", "e.txt"); }, {"e.txt", "no clips"});
}

}  // namespace
}  // namespace jgpm
