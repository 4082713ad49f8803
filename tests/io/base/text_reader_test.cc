#include "io/base/text_reader.h"

#include <cmath>
#include <random>

#include <atomic>
#include <thread>

#include <gtest/gtest.h>

#include "io/base/error.h"
#include "test_support.h"

namespace jgpm {
namespace {

using test::ExpectInputError;
using test::TempDir;

TEST(ReadTextFile, ReadsAFile) {
  TempDir dir;
  EXPECT_EQ(ReadTextFile(dir.Write("a.txt", "hello\n"), "text"), "hello\n");
}

TEST(ReadTextFile, MissingFile) {
  TempDir dir;
  ExpectInputError([&] { ReadTextFile(dir.path() / "nope.asf", "an ASF skeleton"); },
                   {"nope.asf", "no such file", "an ASF skeleton"});
}

TEST(ReadTextFile, DirectoryGivenAsFile) {
  TempDir dir;
  ExpectInputError([&] { ReadTextFile(dir.path(), "an AMC motion"); },
                   {dir.path().string(), "is a directory"});
}

TEST(ReadTextFile, EmptyFile) {
  TempDir dir;
  ExpectInputError([&] { ReadTextFile(dir.Write("e.amc", " \n\n"), "an AMC motion"); },
                   {"e.amc:1", "empty", "an AMC motion"});
}

TEST(ReadTextFile, BinaryFile) {
  TempDir dir;
  ExpectInputError([&] { ReadTextFile(dir.Write("b.bvh", std::string("ab\ncd\0ef", 8)), "a BVH"); },
                   {"b.bvh:2", "NUL"});
}

TEST(LineReader, CountsLinesAndDropsCarriageReturns) {
  LineReader in("one\r\ntwo\n\nfour", "src");
  std::vector<std::string> lines;
  while (in.Next()) lines.emplace_back(in.line());
  EXPECT_EQ(lines, (std::vector<std::string>{"one", "two", "", "four"}));
  EXPECT_EQ(in.line_number(), 4);
  EXPECT_EQ(in.Where(), "src:4");
}

TEST(LineReader, ParseDoubleRejectsNonFiniteAndGarbage) {
  LineReader in("x\n", "f.amc");
  in.Next();
  EXPECT_DOUBLE_EQ(in.ParseDouble("-2.43511e-015", "v"), -2.43511e-15);
  EXPECT_DOUBLE_EQ(in.ParseDouble("+5", "v"), 5.0);
  for (const char* bad : {"nan", "NaN", "inf", "-inf", "1e999", "1.5x", "", "--1", "0x1p3"}) {
    ExpectInputError([&] { in.ParseDouble(bad, "lfemur.rx"); }, {"f.amc:1", "lfemur.rx"});
  }
  EXPECT_TRUE(std::isinf(in.ParseDoubleOrInf("-inf", "limit")));
  ExpectInputError([&] { in.ParseDoubleOrInf("nan", "limit"); }, {"f.amc:1", "limit"});
}

TEST(LineReader, ParseInt) {
  LineReader in("x\n", "f");
  in.Next();
  EXPECT_EQ(in.ParseInt("42", "n"), 42);
  ExpectInputError([&] { in.ParseInt("4.2", "frame count"); }, {"f:1", "integer", "frame count"});
  ExpectInputError([&] { in.ParseInt("99999999999", "n"); }, {"integer"});
}

TEST(FormatShortest, RoundTripsExactly) {
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> uniform(-1e3, 1e3);
  for (int i = 0; i < 20000; ++i) {
    const double value = i % 3 == 0 ? uniform(random) * 1e-17 : uniform(random);
    const std::string text = FormatShortest(value);
    LineReader in("x", "f");
    in.Next();
    EXPECT_EQ(in.ParseDouble(text, "v"), value) << text;
  }
  EXPECT_EQ(FormatShortest(0.1), "0.1");
  EXPECT_EQ(FormatShortest(-2.43511e-15), "-2.43511e-15");
}

TEST(SplitBlanks, SplitsOnSpacesAndTabs) {
  const auto tokens = SplitBlanks("  a\tbb   c  ");
  ASSERT_EQ(tokens.size(), 3u);
  EXPECT_EQ(tokens[1], "bb");
}

TEST(WriteFileAtomic, WritesAndReplaces) {
  TempDir dir;
  const auto path = dir.path() / "out.txt";
  WriteFileAtomic(path, "first");
  WriteFileAtomic(path, "second");
  EXPECT_EQ(ReadTextFile(path, "text"), "second");
  int files = 0;
  for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator(dir.path())) ++files;
  EXPECT_EQ(files, 1);  // no temporary left
  // A new file gets the permissions the umask allows, not mkstemp's private 0600.
  const auto perms = std::filesystem::status(path).permissions();
  EXPECT_NE(perms & std::filesystem::perms::others_read, std::filesystem::perms::none);
}

// Two writers of one file (two jgpm runs, or two threads) must not share a temporary: each
// write lands whole, and neither fails. With one fixed temporary name, one writer's rename
// took the other's half-written file or failed to find its own.
TEST(WriteFileAtomic, ConcurrentWritersNeverMixOrFail) {
  TempDir dir;
  const auto path = dir.path() / "shared.txt";
  const std::string a(200000, 'a'), b(300000, 'b');
  std::atomic<int> failures{0};
  auto writer = [&](const std::string& text) {
    for (int i = 0; i < 40; ++i) {
      try {
        WriteFileAtomic(path, text);
      } catch (const InputError&) {
        ++failures;
      }
    }
  };
  std::thread first(writer, std::cref(a)), second(writer, std::cref(b));
  for (int i = 0; i < 80; ++i) {
    std::string seen;
    try {
      seen = ReadTextFile(path, "text");
    } catch (const InputError&) {
      continue;  // not written yet
    }
    EXPECT_TRUE(seen == a || seen == b) << "a mixed file of " << seen.size() << " bytes";
  }
  first.join();
  second.join();
  EXPECT_EQ(failures.load(), 0);
  const std::string last = ReadTextFile(path, "text");
  EXPECT_TRUE(last == a || last == b);
}

TEST(WriteFileAtomic, MissingFolderIsAnErrorAndLeavesNothing) {
  TempDir dir;
  ExpectInputError([&] { WriteFileAtomic(dir.path() / "no" / "out.txt", "x"); },
                   {"out.txt", "does not exist"});
  ExpectInputError([&] { WriteFileAtomic(dir.path(), "x"); }, {"is a directory"});
}

TEST(Quote, ShortensAndMasksControlCharacters) {
  EXPECT_EQ(Quote("ab"), "'ab'");
  EXPECT_EQ(Quote(std::string("a\x01", 2)), "'a?'");
  EXPECT_EQ(Quote(std::string(100, 'x')).size(), 40u + 2u + 3u);
}

}  // namespace
}  // namespace jgpm
