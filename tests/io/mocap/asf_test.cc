#include "io/mocap/asf.h"

#include <gtest/gtest.h>

#include "test_support.h"

namespace jgpm {
namespace {

using test::ExpectInputError;
using test::MalformedCase;

TEST(Asf, ParsesTheSmallSkeleton) {
  const Skeleton s = ParseAsf(test::SmallAsfText(), "small.asf");
  EXPECT_EQ(s.name, "TEST");
  EXPECT_EQ(s.version, "1.10");
  EXPECT_DOUBLE_EQ(s.length_scale, 0.45);
  EXPECT_DOUBLE_EQ(s.MillimetresPerUnit(), 25.4 / 0.45);
  ASSERT_EQ(s.bones.size(), 5u);
  // Depth-first from the root, children in hierarchy order.
  std::vector<std::string> names;
  for (const Bone& b : s.bones) names.push_back(b.name);
  EXPECT_EQ(names, (std::vector<std::string>{"root", "hip", "thigh", "shin", "spine"}));
  const Bone& root = s.bones[0];
  EXPECT_EQ(root.parent, -1);
  EXPECT_EQ(root.dofs, (std::vector<Dof>{Dof::kTx, Dof::kTy, Dof::kTz, Dof::kRx, Dof::kRy, Dof::kRz}));
  EXPECT_EQ(root.children, (std::vector<int>{1, 4}));
  const Bone& thigh = s.bones[s.FindBone("thigh")];
  EXPECT_EQ(thigh.id, 2);
  EXPECT_EQ(s.bones[thigh.parent].name, "hip");
  EXPECT_TRUE(thigh.direction.isApprox(Eigen::Vector3d(0, -1, 0)));
  EXPECT_DOUBLE_EQ(thigh.length, 4);
  EXPECT_TRUE(thigh.axis_deg.isApprox(Eigen::Vector3d(0, 0, 90)));
  EXPECT_EQ(AxisOrderName(thigh.axis_order), "XYZ");
  EXPECT_EQ(thigh.dofs, (std::vector<Dof>{Dof::kRx, Dof::kRz}));
  ASSERT_EQ(thigh.limits.size(), 2u);
  EXPECT_DOUBLE_EQ(thigh.limits[0].min, -160);
  EXPECT_DOUBLE_EQ(thigh.limits[1].max, 70);
  const Bone& spine = s.bones[s.FindBone("spine")];
  ASSERT_EQ(spine.limits.size(), 3u);  // two pairs on one line
  EXPECT_TRUE(std::isinf(spine.limits[0].min));
  EXPECT_DOUBLE_EQ(spine.limits[2].min, -30);
  EXPECT_EQ(s.NumChannels(), 6 + 2 + 1 + 3);
  EXPECT_EQ(s.ChannelOffsets(), (std::vector<int>{0, 6, 6, 8, 9, 12}));
  EXPECT_EQ(s.ChannelNames()[6], "thigh.rx");
}

TEST(Asf, RadiansAreConvertedToDegrees) {
  std::string text = test::Replace(test::SmallAsfText(), "angle deg", "angle rad");
  text = test::Replace(text, "axis 0 0 90  XYZ", "axis 0 0 1.5707963267948966  XYZ");
  const Skeleton s = ParseAsf(text, "rad.asf");
  EXPECT_NEAR(s.bones[s.FindBone("thigh")].axis_deg.z(), 90, 1e-12);
}

TEST(Asf, ToleratesCrlfAndNonUnitDirections) {
  std::string text = test::SmallAsfText();
  text = test::Replace(text, "direction 0 1 0", "direction 0 2 0");
  std::string crlf;
  for (char c : text) crlf += c == '\n' ? std::string("\r\n") : std::string(1, c);
  const Skeleton s = ParseAsf(crlf, "crlf.asf");
  EXPECT_TRUE(s.bones[s.FindBone("spine")].direction.isApprox(Eigen::Vector3d(0, 1, 0)));
}

TEST(Asf, ReadsEveryCmuSkeleton) {
  int count = 0;
  for (const auto& subject : std::filesystem::directory_iterator(test::CmuRoot() / "subjects")) {
    const auto path = subject.path() / (subject.path().filename().string() + ".asf");
    const Skeleton s = ReadAsf(path);
    SCOPED_TRACE(path.string());
    EXPECT_EQ(s.bones.size(), 31u);   // root + 30 bones
    EXPECT_EQ(s.NumChannels(), 62);   // SOURCES.md: 62 values per frame
    EXPECT_DOUBLE_EQ(s.length_scale, 0.45);
    EXPECT_EQ(s.bones[s.FindBone("lfemur")].dofs.size(), 3u);
    EXPECT_EQ(s.bones[s.bones[s.FindBone("lfemur")].parent].name, "lhipjoint");
    for (size_t b = 1; b < s.bones.size(); ++b) EXPECT_LT(s.bones[b].parent, static_cast<int>(b));
    ++count;
  }
  EXPECT_GE(count, 11);
}

TEST(Asf, TruncatedInsideABoneBlock) {
  const std::string text = test::SmallAsfText();
  const size_t cut = text.find("    dof rx\n") + 11;  // shin's dof line, before its limits
  ExpectInputError([&] { ParseAsf(text.substr(0, cut), "cut.asf"); },
                   {"cut.asf:" + std::to_string(test::LineOf(text, "id 3") - 1),
                    "file ends inside a bone block"});
}

TEST(Asf, EveryTruncationBeforeTheLastLinkIsAnError) {
  const std::string text = test::SmallAsfText();
  const size_t complete = text.find("thigh shin") + 10;  // the hierarchy's last link
  const size_t end = text.find("end", complete);          // a cut inside it leaves garbage
  for (size_t cut = 0; cut < text.size(); ++cut) {
    if (cut < complete || (cut > end && cut < end + 3)) {
      EXPECT_THROW(ParseAsf(text.substr(0, cut), "cut.asf"), InputError) << cut;
    } else {
      EXPECT_NO_THROW(ParseAsf(text.substr(0, cut), "cut.asf")) << cut;
    }
  }
}

TEST(Asf, EmptyAndDirectoryInputs) {
  test::TempDir dir;
  ExpectInputError([&] { ReadAsf(dir.Write("empty.asf", "")); }, {"empty.asf:1", "empty"});
  ExpectInputError([&] { ReadAsf(dir.path()); }, {"is a directory"});
}

class AsfMalformed : public testing::TestWithParam<MalformedCase> {};

TEST_P(AsfMalformed, NamesFileLineAndExpectation) {
  test::ExpectMalformed(GetParam(), test::SmallAsfText(), "bad.asf",
                        [](const std::string& text, const std::string& source) { ParseAsf(text, source); });
}

INSTANTIATE_TEST_SUITE_P(
    Cases, AsfMalformed,
    testing::Values(
        MalformedCase{"NoHierarchy",
                      ":hierarchy\n  begin\n    root hip spine\n    hip thigh\n    thigh shin\n  end\n",
                      "", "", "missing :hierarchy"},
        MalformedCase{"UnknownBoneInHierarchy", "thigh shin", "thigh knee", "thigh knee",
                      "unknown bone 'knee'"},
        MalformedCase{"NanLength", "length 4", "length nan", "length nan", "finite number for length"},
        MalformedCase{"InfAxis", "axis 0 0 90", "axis 0 inf 90", "axis 0 inf", "finite number for axis"},
        MalformedCase{"TooFewDirectionValues", "direction 0 -1 0\n     length 4",
                      "direction 0 -1\n     length 4", "direction 0 -1\n", "expected a direction"},
        MalformedCase{"TooFewLimits", "\n           (-70.0 70.0)", "", "limits (-160.0 20.0)",
                      "expected 2 limit pairs"},
        MalformedCase{"LimitNotANumber", "(-10.0 170.0)", "(-10.0 abc)", "(-10.0 abc)", "limit maximum"},
        MalformedCase{"UnclosedLimit", "(-10.0 170.0)", "(-10.0 170.0", "(-10.0 170.0", "')'"},
        MalformedCase{"BadAxisOrder", "axis 0 0 90  XYZ", "axis 0 0 90  XYX", "XYX", "axis order"},
        MalformedCase{"UnknownDof", "dof rx rz", "dof rx rw", "dof rx rw", "expected a dof"},
        MalformedCase{"RepeatedDof", "dof rx rz", "dof rx rx", "dof rx rx", "listed twice"},
        MalformedCase{"TranslationDofOnBone", "dof rx rz", "dof rx tz", "dof rx tz", "root only"},
        MalformedCase{"LimitsBeforeDof", "    dof rx\n    limits (-10.0 170.0)",
                      "    limits (-10.0 170.0)\n    dof rx", "limits (-10.0 170.0)", "before 'limits'"},
        MalformedCase{"MissingRootSection", ":root", ":documentation", "", "missing :root"},
        MalformedCase{"MissingRootOrder", "order TX TY TZ RX RY RZ", "", "", "no 'order'"},
        MalformedCase{"DuplicateBone", "name spine", "name thigh", "name thigh\n     direction 0 1 0",
                      "defined twice"},
        MalformedCase{"UnknownSection", ":documentation", ":colour", ":colour", "unknown section"},
        MalformedCase{"UnknownBoneField", "     length 3", "     colour 3", "colour 3",
                      "unknown bone field"},
        MalformedCase{"NotConnected", "    thigh shin\n", "", "", "'shin' is not connected"},
        MalformedCase{"SecondParent", "    thigh shin\n", "    thigh shin\n    hip shin\n",
                      "hip shin", "second parent"},
        MalformedCase{"RootAsChild", "    thigh shin\n", "    thigh shin root\n", "thigh shin root",
                      "root cannot be a child"},
        MalformedCase{"ZeroDirection", "direction 0 1 0", "direction 0 0 0", "end\n:hierarchy",
                      "zero direction"},
        MalformedCase{"MissingLength", "     length 5\n", "", "end\n:hierarchy", "lacks required"},
        MalformedCase{"BadAngleUnit", "angle deg", "angle grad", "angle grad", "'deg' or 'rad'"},
        MalformedCase{"NegativeLengthUnit", "length 0.45", "length -1", "length -1", "length unit > 0"},
        MalformedCase{"BeginMissing", "  begin\n     id 4", "     id 4", "id 4", "expected 'begin'"},
        MalformedCase{"EndMissing", "  end\n:hierarchy", ":hierarchy", ":hierarchy",
                      "expected 'end'"}),
    test::CaseName);

}  // namespace
}  // namespace jgpm
