// The tracking suite's file format: the shipped suite parses to the clips it lists, and
// each malformed line is refused naming the file, the line and what was expected.
#include "tracker/clip/tracking_suite.h"

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
