#include "io/mocap/motion_file.h"

#include <gtest/gtest.h>

#include "io/base/text_reader.h"
#include "io/mocap/amc.h"
#include "io/mocap/asf.h"
#include "io/mocap/bvh.h"
#include "small_asf.h"
#include "test_support.h"

namespace jgpm {
namespace {

using test::ExpectInputError;
namespace fs = std::filesystem;

const fs::path kAsf = "subjects/07/07.asf";
const fs::path kAmc = "subjects/07/07_01.amc";

TEST(MotionFile, FormatFromExtension) {
  EXPECT_EQ(FormatFromPath("a/B.AMC", "x"), MotionFormat::kAmc);
  EXPECT_EQ(FormatFromPath("b.bvh", "x"), MotionFormat::kBvh);
  ExpectInputError([] { FormatFromPath("c.fbx", "--out"); }, {"--out", ".asf, .amc or .bvh"});
}

TEST(MotionFile, DescribesEachFormat) {
  const fs::path root = test::CmuRoot();
  const std::string asf = DescribeMotionFile(root / kAsf, {});
  EXPECT_NE(asf.find("31 bones"), std::string::npos) << asf;
  EXPECT_NE(asf.find("62 channels"), std::string::npos) << asf;
  // The AMC finds its skeleton next to it.
  const std::string amc = DescribeMotionFile(root / kAmc, {});
  EXPECT_NE(amc.find("frames 316"), std::string::npos) << amc;
  EXPECT_NE(amc.find("2.63 s"), std::string::npos) << amc;
  EXPECT_NE(amc.find("channels 62"), std::string::npos) << amc;
}

TEST(MotionFile, AmcWithoutSkeleton) {
  test::TempDir dir;
  const fs::path amc = dir.Write("x_01.amc", ":FULLY-SPECIFIED\n:DEGREES\n1\n");
  ExpectInputError([&] { DescribeMotionFile(amc, {}); }, {"x_01.amc", "--asf"});
  ExpectInputError([&] { DescribeMotionFile(dir.path() / "none.amc", {}); }, {"none.amc", "no such file"});
}

// jgpm writes OUT.amc with OUT.asf beside it; that pairing is found first.
TEST(MotionFile, AmcFindsTheSkeletonOfTheSameName) {
  test::TempDir dir;
  dir.Write("walk_3.asf", test::SmallAsfText());
  const Skeleton skeleton = ParseAsf(test::SmallAsfText(), "small");
  Motion motion;
  motion.values = RowMatrixXd::Zero(2, skeleton.NumChannels());
  WriteAmc(dir.path() / "walk_3.amc", motion, skeleton);
  const std::string text = DescribeMotionFile(dir.path() / "walk_3.amc", {});
  EXPECT_NE(text.find("walk_3.asf"), std::string::npos) << text;
  ExpectInputError([&] { DescribeMotionFile(dir.path() / "other_3.amc", {}); }, {"other_3.amc"});
}

TEST(MotionFile, ConvertsBothWaysKeepingTheMotion) {
  const fs::path root = test::CmuRoot();
  test::TempDir dir;
  MotionFileOptions options;
  const std::string to_bvh = ConvertMotionFile(root / kAmc, dir.path() / "a.bvh", options);
  EXPECT_NE(to_bvh.find("316 frames"), std::string::npos) << to_bvh;
  options.asf = root / kAsf;
  ConvertMotionFile(dir.path() / "a.bvh", dir.path() / "a.amc", options);
  const Skeleton s = ReadAsf(root / kAsf);
  const Motion original = ReadAmc(root / kAmc, s);
  const Motion back = ReadAmc(dir.path() / "a.amc", s);
  ASSERT_EQ(back.NumFrames(), original.NumFrames());
  // Angles may come back wrapped by 360 degrees; the root translation exactly.
  EXPECT_LT((back.values.leftCols(3) - original.values.leftCols(3)).cwiseAbs().maxCoeff(), 1e-9);
  const Bvh bvh = ReadBvh(dir.path() / "a.bvh");
  EXPECT_NEAR(bvh.frame_time, 1.0 / 120.0, 1e-15);
}

TEST(MotionFile, RefusesToOverwriteTheInput) {
  const fs::path root = test::CmuRoot();
  test::TempDir dir;
  const fs::path bvh = dir.path() / "a.bvh";
  ConvertMotionFile(root / kAmc, bvh, {});
  ExpectInputError([&] { ConvertMotionFile(bvh, bvh, {}); }, {"--out", "is the input"});
}

TEST(MotionFile, FailedConversionLeavesTheOutputUntouched) {
  const fs::path root = test::CmuRoot();
  test::TempDir dir;
  const fs::path out = dir.Write("keep.bvh", "precious");
  const fs::path bad = dir.Write("07_99.amc", ":FULLY-SPECIFIED\n:DEGREES\n1\nroot 1 2 3\n");
  MotionFileOptions options;
  options.asf = root / kAsf;
  ExpectInputError([&] { ConvertMotionFile(bad, out, options); }, {"07_99.amc:4"});
  EXPECT_EQ(ReadTextFile(out, "text"), "precious");
  // BVH -> AMC needs the skeleton.
  ExpectInputError([&] { ConvertMotionFile(out, dir.path() / "x.amc", {}); }, {"--asf"});
  ExpectInputError([&] { ConvertMotionFile(root / kAsf, dir.path() / "x.bvh", {}); }, {"is a skeleton"});
}

}  // namespace
}  // namespace jgpm
