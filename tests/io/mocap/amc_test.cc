#include "io/mocap/amc.h"

#include <gtest/gtest.h>

#include "io/mocap/asf.h"
#include "test_support.h"

namespace jgpm {
namespace {

using test::ExpectInputError;
using test::MalformedCase;

const char kSmallAmc[] = R"(#!OML:ASF small.asf
:FULLY-SPECIFIED
:DEGREES
1
root 1 2 3 0 90 0
thigh 10 20
shin 30
spine 1 2 3
2
spine 4 5 6
root -1.5 2.25e-3 -2.43511e-015 0 0 0
thigh 11 21
shin 31
)";

Skeleton Small() { return ParseAsf(test::SmallAsfText(), "small.asf"); }

TEST(Amc, ParsesFramesIntoSkeletonChannelOrder) {
  const Skeleton s = Small();
  const Motion m = ParseAmc(kSmallAmc, "small.amc", s);
  ASSERT_EQ(m.NumFrames(), 2);
  ASSERT_EQ(m.values.cols(), 12);
  EXPECT_EQ(m.first_frame_number, 1);
  EXPECT_EQ(m.header_comments, (std::vector<std::string>{"#!OML:ASF small.asf"}));
  // Channels: root(6) thigh(2) shin(1) spine(3), whatever order the file lists bones in.
  Eigen::RowVectorXd frame0(12), frame1(12);
  frame0 << 1, 2, 3, 0, 90, 0, 10, 20, 30, 1, 2, 3;
  frame1 << -1.5, 2.25e-3, -2.43511e-15, 0, 0, 0, 11, 21, 31, 4, 5, 6;
  EXPECT_EQ(m.values.row(0), frame0);
  EXPECT_EQ(m.values.row(1), frame1);
  EXPECT_EQ(m.bone_order, (std::vector<int>{0, 2, 3, 4}));  // as in the first frame
}

TEST(Amc, WriteReadReproducesTheNumbersExactly) {
  const Skeleton s = Small();
  const Motion m = ParseAmc(kSmallAmc, "small.amc", s);
  const std::string text = FormatAmc(m, s);
  const Motion back = ParseAmc(text, "back.amc", s);
  EXPECT_EQ(back.values, m.values);
  EXPECT_EQ(back.header_comments, m.header_comments);
  EXPECT_EQ(FormatAmc(back, s), text);
}

// Every CMU trial: write(read(file)) reads back to bit-identical values, and formatting
// again gives the same text.
TEST(Amc, RoundTripIsExactOnEveryCmuTrial) {
  std::map<std::filesystem::path, Skeleton> skeletons;
  int trials = 0;
  long values = 0;
  for (const test::CmuTrial& trial : test::AllCmuTrials()) {
    SCOPED_TRACE(trial.amc.string());
    auto it = skeletons.find(trial.asf);
    if (it == skeletons.end()) it = skeletons.emplace(trial.asf, ReadAsf(trial.asf)).first;
    const Motion m = ReadAmc(trial.amc, it->second);
    const std::string text = FormatAmc(m, it->second);
    const Motion back = ParseAmc(text, "back.amc", it->second);
    ASSERT_EQ(back.values.rows(), m.values.rows());
    EXPECT_TRUE((back.values.array() == m.values.array()).all());
    EXPECT_EQ(FormatAmc(back, it->second), text);
    ++trials;
    values += m.values.size();
  }
  EXPECT_GE(trials, 70);
  std::cout << "round-tripped " << trials << " CMU trials, " << values << " values exactly\n";
}

TEST(Amc, ReadsACmuTrialWithTheExpectedShape) {
  const Skeleton s = ReadAsf(test::CmuRoot() / "subjects/07/07.asf");
  const Motion m = ReadAmc(test::CmuRoot() / "subjects/07/07_01.amc", s);
  EXPECT_EQ(m.NumFrames(), 316);  // SOURCES.md
  EXPECT_EQ(m.values.cols(), 62);
  // First frame, first line of the file: root 8.87208 15.7511 -31.7081 5.5217 4.9122 3.70117
  EXPECT_DOUBLE_EQ(m.values(0, 0), 8.87208);
  EXPECT_DOUBLE_EQ(m.values(0, 5), 3.70117);
}

TEST(Amc, AnAmcOfAnotherSkeletonIsRejected) {
  const Skeleton s = Small();
  ExpectInputError([&] { ReadAmc(test::CmuRoot() / "subjects/07/07_01.amc", s); },
                   {"07_01.amc:6", "unknown bone 'lowerback'"});
}

TEST(Amc, EmptyFileAndDirectory) {
  const Skeleton s = Small();
  test::TempDir dir;
  ExpectInputError([&] { ReadAmc(dir.Write("e.amc", "\n"), s); }, {"e.amc:1", "empty"});
  ExpectInputError([&] { ReadAmc(dir.path(), s); }, {"is a directory"});
}

TEST(Amc, HeaderWithoutFrames) {
  ExpectInputError([&] { ParseAmc(":FULLY-SPECIFIED\n:DEGREES\n", "h.amc", Small()); },
                   {"h.amc:2", "expected frames after the header"});
}

TEST(Amc, EveryTruncationIsAnErrorUnlessAtAFrameEnd) {
  const Skeleton s = Small();
  const std::string text = kSmallAmc;
  const size_t frame1_end = text.find("2\nspine");  // after frame 1's last line
  for (size_t cut = 0; cut < text.size(); ++cut) {
    // A cut inside the last number leaves a shorter valid number (AMC has no end marker).
    const bool complete = cut == frame1_end || cut == frame1_end - 1 || cut >= text.size() - 2;
    if (complete) {
      EXPECT_NO_THROW(ParseAmc(text.substr(0, cut), "cut.amc", s)) << cut;
    } else {
      EXPECT_THROW(ParseAmc(text.substr(0, cut), "cut.amc", s), InputError) << cut;
    }
  }
}

class AmcMalformed : public testing::TestWithParam<MalformedCase> {};

TEST_P(AmcMalformed, NamesFileLineAndExpectation) {
  test::ExpectMalformed(GetParam(), kSmallAmc, "bad.amc",
                        [](const std::string& text, const std::string& source) { ParseAmc(text, source, Small()); });
}

INSTANTIATE_TEST_SUITE_P(
    Cases, AmcMalformed,
    testing::Values(
        MalformedCase{"TruncatedLastFrame", "shin 31\n", "", "thigh 11 21", "file ends inside frame 2"},
        MalformedCase{"TooFewValues", "thigh 10 20", "thigh 10", "thigh 10", "expected 2 value(s) for bone 'thigh'"},
        MalformedCase{"TooManyValues", "shin 30", "shin 30 40", "shin 30 40", "expected 1 value(s)"},
        MalformedCase{"UnknownBone", "shin 30", "knee 30", "knee 30", "unknown bone 'knee'"},
        MalformedCase{"BoneWithoutDofs", "shin 30", "shin 30\nhip 0", "hip 0", "has no dofs"},
        MalformedCase{"NanValue", "shin 30", "shin nan", "shin nan", "finite number for shin.rx"},
        MalformedCase{"InfValue", "spine 4 5 6", "spine 4 inf 6", "spine 4 inf", "finite number for spine.ry"},
        MalformedCase{"NotANumber", "thigh 11 21", "thigh 11 2l", "thigh 11 2l", "expected a number"},
        MalformedCase{"MissingDegrees", ":DEGREES\n", "", "1\nroot", "expected :DEGREES"},
        MalformedCase{"MissingFullySpecified", ":FULLY-SPECIFIED\n", "", "1\nroot", "expected :FULLY-SPECIFIED"},
        MalformedCase{"Radians", ":DEGREES", ":RADIANS", ":RADIANS", "expected :DEGREES"},
        MalformedCase{"GarbageInHeader", ":DEGREES\n", ":DEGREES\nhello\n", "hello", "expected :FULLY-SPECIFIED"},
        MalformedCase{"MissingBoneInFrame", "shin 30\n", "", "2\nspine", "frame 1 (started at line 4) lacks 1 bone(s): shin"},
        MalformedCase{"RepeatedBone", "shin 30\n", "shin 30\nshin 30\n", "shin 30\nspine", "appears twice"},
        MalformedCase{"SkippedFrameNumber", "2\nspine", "3\nspine", "3\nspine", "expected frame number 2"},
        // The next number after INT_MAX overflowed an int (undefined behaviour), and a
        // number past an int was taken for a bone's name.
        MalformedCase{"FirstFrameNumberAtIntMax", "1\nroot", "2147483647\nroot", "2147483647", "is out of range"},
        MalformedCase{"FrameNumberPastAnInt", "2\nspine", "2147483648\nspine", "2147483648",
                      "expected frame number 2, found 2147483648"}),
    test::CaseName);

}  // namespace
}  // namespace jgpm
