#include "io/mocap/bvh.h"

// This program replaces operator new (to see its largest allocation) with malloc and free;
// GCC cannot tell that the pair matches.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
#endif

#include <atomic>
#include <cstdlib>
#include <new>

#include <gtest/gtest.h>

#include "test_support.h"

namespace jgpm {
namespace test {
std::atomic<size_t> largest_allocation{0};
}  // namespace test
namespace {

using test::ExpectInputError;
using test::MalformedCase;

const char kSmallBvh[] = R"(HIERARCHY
ROOT Hips
{
  OFFSET 0 0 0
  CHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation
  JOINT Chest
  {
    OFFSET 0 10 0
    CHANNELS 3 Zrotation Xrotation Yrotation
    End Site
    {
      OFFSET 0 5 0
    }
  }
  JOINT Leg
  {
    OFFSET 3 0 0
    CHANNELS 3 Xrotation Yrotation Zrotation
    End Site
    {
      OFFSET 0 -8 0
    }
  }
}
MOTION
Frames: 3
Frame Time: 0.0333333
0 0 0 0 0 0 0 0 0 0 0 0
1 2 3 0 0 90 90 0 0 0 0 0
0 0 0 90 90 0 0 0 0 0 0 0
)";

TEST(Bvh, ParsesHierarchyAndFrames) {
  const Bvh bvh = ParseBvh(kSmallBvh, "small.bvh");
  ASSERT_EQ(bvh.joints.size(), 5u);  // Hips, Chest, its End Site, Leg, its End Site
  EXPECT_EQ(bvh.joints[0].name, "Hips");
  EXPECT_EQ(bvh.joints[0].parent, -1);
  EXPECT_EQ(bvh.joints[2].end_site, true);
  EXPECT_EQ(bvh.joints[2].parent, 1);
  EXPECT_EQ(bvh.joints[3].parent, 0);
  EXPECT_EQ(bvh.FindJoint("Leg"), 3);
  EXPECT_EQ(bvh.NumChannels(), 12);
  EXPECT_EQ(bvh.ChannelOffsets(), (std::vector<int>{0, 6, 9, 9, 12, 12}));
  EXPECT_EQ(bvh.frames.rows(), 3);
  EXPECT_DOUBLE_EQ(bvh.frame_time, 0.0333333);
  EXPECT_DOUBLE_EQ(bvh.frames(1, 5), 90);
}

// Hand-computed positions in millimetres (10 mm per unit).
TEST(Bvh, ForwardKinematicsByHand) {
  const Bvh bvh = ParseBvh(kSmallBvh, "small.bvh");
  Eigen::Matrix3Xd j;
  ComputeBvhPose(bvh, 0, &j);
  EXPECT_TRUE(j.col(1).isApprox(Eigen::Vector3d(0, 100, 0)));
  EXPECT_TRUE(j.col(2).isApprox(Eigen::Vector3d(0, 150, 0)));
  EXPECT_TRUE(j.col(4).isApprox(Eigen::Vector3d(30, -80, 0)));
  // Frame 2: root at (10,20,30) mm turned Ry(90); the chest turns a further Rz(90).
  ComputeBvhPose(bvh, 1, &j);
  EXPECT_LT((j.col(0) - Eigen::Vector3d(10, 20, 30)).norm(), 1e-9);
  EXPECT_LT((j.col(1) - Eigen::Vector3d(10, 120, 30)).norm(), 1e-9);
  EXPECT_LT((j.col(2) - Eigen::Vector3d(10, 120, 80)).norm(), 1e-9);
  EXPECT_LT((j.col(3) - Eigen::Vector3d(10, 20, 0)).norm(), 1e-9);
  EXPECT_LT((j.col(4) - Eigen::Vector3d(10, -60, 0)).norm(), 1e-9);
}

TEST(Bvh, ChannelsMultiplyInTheirListedOrder) {
  // Root "Zrotation Xrotation Yrotation" = (90, 90, 0): R = Rz(90) Rx(90) takes the chest
  // offset (0,100,0) to (0,0,100). Rx Rz would give (-100,0,0).
  const Bvh bvh = ParseBvh(kSmallBvh, "small.bvh");
  Eigen::Matrix3Xd j;
  std::vector<Eigen::Matrix3d> rotations;
  ComputeBvhPose(bvh, 2, &j, &rotations);
  EXPECT_LT((j.col(1) - Eigen::Vector3d(0, 0, 100)).norm(), 1e-9);
  EXPECT_TRUE(rotations[0].isApprox(AxisRotation(Axis::kZ, 90) * AxisRotation(Axis::kX, 90)));
}

TEST(Bvh, UnitIsAnOption) {
  const Bvh bvh = ParseBvh(kSmallBvh, "small.bvh", /*mm_per_unit=*/25.4);
  Eigen::Matrix3Xd j;
  ComputeBvhPose(bvh, 0, &j);
  EXPECT_NEAR(j.col(1).y(), 254.0, 1e-9);
}

TEST(Bvh, FormatThenParseIsExact) {
  const Bvh bvh = ParseBvh(kSmallBvh, "small.bvh");
  const std::string text = FormatBvh(bvh);
  const Bvh back = ParseBvh(text, "back.bvh");
  ASSERT_EQ(back.joints.size(), bvh.joints.size());
  for (size_t j = 0; j < bvh.joints.size(); ++j) {
    EXPECT_EQ(back.joints[j].name, bvh.joints[j].name);
    EXPECT_EQ(back.joints[j].parent, bvh.joints[j].parent);
    EXPECT_EQ(back.joints[j].offset, bvh.joints[j].offset);
    EXPECT_EQ(back.joints[j].channels, bvh.joints[j].channels);
  }
  EXPECT_EQ(back.frames, bvh.frames);
  EXPECT_EQ(back.frame_time, bvh.frame_time);
  EXPECT_EQ(FormatBvh(back), text);
}

TEST(Bvh, AcceptsBracesOnNameLinesAndCrlf) {
  std::string text = test::Replace(kSmallBvh, "JOINT Chest\n  {", "JOINT Chest {");
  std::string crlf;
  for (char c : text) crlf += c == '\n' ? std::string("\r\n") : std::string(1, c);
  EXPECT_EQ(ParseBvh(crlf, "crlf.bvh").joints.size(), 5u);
}

TEST(Bvh, EveryTruncationIsAnErrorUnlessInTheLastNumber) {
  const std::string text = kSmallBvh;
  for (size_t cut = 0; cut + 1 < text.size(); ++cut) {
    EXPECT_THROW(ParseBvh(text.substr(0, cut), "cut.bvh"), InputError) << cut;
  }
  EXPECT_NO_THROW(ParseBvh(text.substr(0, text.size() - 1), "cut.bvh"));
}

class BvhMalformed : public testing::TestWithParam<MalformedCase> {};

TEST_P(BvhMalformed, NamesFileLineAndExpectation) {
  test::ExpectMalformed(GetParam(), kSmallBvh, "bad.bvh",
                        [](const std::string& text, const std::string& source) { ParseBvh(text, source); });
}

INSTANTIATE_TEST_SUITE_P(
    Cases, BvhMalformed,
    testing::Values(
        MalformedCase{"NoHierarchyKeyword", "HIERARCHY", "HIERARCHX", "HIERARCHX", "expected HIERARCHY"},
        MalformedCase{"NoRoot", "ROOT Hips", "JOINT Hips", "JOINT Hips", "expected ROOT"},
        MalformedCase{"MissingOpenBrace", "JOINT Leg\n  {", "JOINT Leg", "OFFSET 3 0 0", "expected '{'"},
        MalformedCase{"MissingOffset", "    OFFSET 3 0 0\n", "", "Xrotation Yrotation Zrotation", "expected OFFSET"},
        MalformedCase{"ShortOffset", "OFFSET 3 0 0", "OFFSET 3 0", "Xrotation Yrotation Zrotation", "number for OFFSET"},
        MalformedCase{"NanOffset", "OFFSET 3 0 0", "OFFSET 3 nan 0", "OFFSET 3 nan", "finite number for OFFSET"},
        MalformedCase{"MissingChannels", "    CHANNELS 3 Zrotation Xrotation Yrotation\n", "", "End Site", "expected CHANNELS"},
        MalformedCase{"BadChannelName", "Xrotation Yrotation Zrotation", "Xrotation Yrotation Wrotation", "Wrotation", "expected a channel name"},
        MalformedCase{"ChannelCountTooHigh", "CHANNELS 3 Zrotation", "CHANNELS 4 Zrotation", "End Site", "expected a channel name"},
        MalformedCase{"ChannelCountOutOfRange", "CHANNELS 3 Zrotation", "CHANNELS 7 Zrotation", "CHANNELS 7", "from 0 to 6"},
        MalformedCase{"RepeatedChannel", "Xrotation Yrotation Zrotation", "Xrotation Yrotation Yrotation", "Yrotation Yrotation", "listed twice"},
        MalformedCase{"EndSiteWithChildren", "OFFSET 0 5 0\n", "OFFSET 0 5 0\n      JOINT X\n", "JOINT X", "cannot have children"},
        MalformedCase{"SecondRoot", "  JOINT Leg", "  ROOT Leg", "ROOT Leg", "one ROOT only"},
        MalformedCase{"DuplicateJointName", "JOINT Leg", "JOINT Chest", "JOINT Chest\n  {\n    OFFSET 3", "defined twice"},
        MalformedCase{"UnclosedHierarchy", "}\nMOTION", "MOTION", "MOTION", "before MOTION"},
        MalformedCase{"StrayToken", "  JOINT Leg", "  BONE Leg", "BONE Leg", "expected JOINT, End Site or '}'"},
        MalformedCase{"MissingMotion", "MOTION\n", "", "Frames:", "expected MOTION"},
        MalformedCase{"BadFrameCount", "Frames: 3", "Frames: three", "Frames:", "integer for frame count"},
        MalformedCase{"ZeroFrames", "Frames: 3", "Frames: 0", "Frames:", "at least 1"},
        MalformedCase{"MissingFrameTime", "Frame Time: 0.0333333", "Frame Tme: 0.0333333", "Frame Tme", "'Frame Time:'"},
        MalformedCase{"ZeroFrameTime", "Frame Time: 0.0333333", "Frame Time: 0", "Frame Time", "frame time > 0"},
        MalformedCase{"TruncatedFrames", "0 0 0 90 90 0 0 0 0 0 0 0\n", "", "1 2 3 0 0 90", "file ends after 2 of 3 frames"},
        MalformedCase{"TooFewValues", "1 2 3 0 0 90 90 0 0 0 0 0", "1 2 3 0 0 90 90 0 0 0 0", "1 2 3 0 0 90", "expected 12 channel values in frame 2, found 11"},
        MalformedCase{"NanValue", "1 2 3 0 0 90", "1 2 nan 0 0 90", "1 2 nan", "finite number for channel value"},
        MalformedCase{"ExtraFrames", "0 0 0 90 90 0 0 0 0 0 0 0\n", "0 0 0 90 90 0 0 0 0 0 0 0\n1 1\n", "1 1\n", "3 declared frames"}),
    test::CaseName);

TEST(Bvh, EmptyFileAndDirectory) {
  test::TempDir dir;
  ExpectInputError([&] { ReadBvh(dir.Write("e.bvh", "")); }, {"e.bvh:1", "empty"});
  ExpectInputError([&] { ReadBvh(dir.path()); }, {"is a directory"});
}

// A 100 KB header with thousands of channels and a huge declared frame count: the parser
// must not ask for memory the file cannot fill (it reserved frames x channels doubles,
// gigabytes, before reading a single frame).
TEST(Bvh, MemoryIsBoundedByWhatTheFileHolds) {
  std::string text = "HIERARCHY\nROOT r\n{\nOFFSET 0 0 0\nCHANNELS 3 Zrotation Xrotation Yrotation\n";
  const int joints = 3000;
  for (int i = 0; i < joints; ++i) {
    text += "JOINT j" + std::to_string(i) + "\n{\nOFFSET 0 1 0\nCHANNELS 3 Zrotation Xrotation Yrotation\n}\n";
  }
  text += "}\nMOTION\nFrames: 100000\nFrame Time: 0.01\n";
  for (int c = 0; c < 3 * (joints + 1); ++c) text += "0 ";
  text += "\n";
  test::largest_allocation = 0;
  ExpectInputError([&] { ParseBvh(text, "wide.bvh"); }, {"file ends after 1 of 100000 frames"});
  EXPECT_LT(test::largest_allocation.load(), 16 * text.size()) << "for a file of " << text.size() << " bytes";
}

TEST(Bvh, DeepNestingDoesNotOverflowTheStack) {
  std::string text = "HIERARCHY\nROOT r\n{\nOFFSET 0 0 0\nCHANNELS 0\n";
  const int depth = 100000;
  for (int i = 0; i < depth; ++i) text += "JOINT j" + std::to_string(i) + "\n{\nOFFSET 0 1 0\nCHANNELS 0\n";
  // Unclosed: the parser reports it without recursing.
  ExpectInputError([&] { ParseBvh(text, "deep.bvh"); }, {"file ends early"});
}

}  // namespace
}  // namespace jgpm

// The largest single allocation of this test program, for the memory bound above.
void* operator new(std::size_t size) {
  size_t seen = jgpm::test::largest_allocation.load();
  while (size > seen && !jgpm::test::largest_allocation.compare_exchange_weak(seen, size)) {
  }
  if (void* p = std::malloc(size ? size : 1)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
