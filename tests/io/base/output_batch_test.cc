// Output batches: every file appears, or none does and existing files are untouched.
#include "io/base/output_batch.h"

#include <gtest/gtest.h>

#include "io/base/text_reader.h"
#include "test_support.h"

namespace jgpm {
namespace {

namespace fs = std::filesystem;

int FilesIn(const fs::path& folder) {
  int n = 0;
  for ([[maybe_unused]] const auto& entry : fs::directory_iterator(folder)) ++n;
  return n;
}

TEST(OutputBatch, CommitMovesEveryFileIntoPlace) {
  test::TempDir dir;
  WriteFileAtomic(dir.path() / "b.txt", "old b");
  OutputBatch batch;
  batch.Add(dir.path() / "a.txt", "new a");
  batch.Add(dir.path() / "b.txt", "new b");
  EXPECT_EQ(ReadTextFile(dir.path() / "b.txt", "text"), "old b");  // nothing moves before Commit
  EXPECT_FALSE(fs::exists(dir.path() / "a.txt"));
  const std::vector<fs::path> written = batch.Commit();
  ASSERT_EQ(written.size(), 2u);
  EXPECT_EQ(ReadTextFile(dir.path() / "a.txt", "text"), "new a");
  EXPECT_EQ(ReadTextFile(dir.path() / "b.txt", "text"), "new b");
  EXPECT_EQ(FilesIn(dir.path()), 2);
}

// A failure after some files were added (here: the third has no folder) leaves nothing
// new and the old files as they were.
TEST(OutputBatch, AFailureHalfWayLeavesNothing) {
  test::TempDir dir;
  WriteFileAtomic(dir.path() / "keep.txt", "old");
  try {
    OutputBatch batch;
    batch.Add(dir.path() / "keep.txt", "replaced?");
    batch.Add(dir.path() / "new.txt", "new");
    batch.Add(dir.path() / "missing" / "c.txt", "c");
    batch.Commit();
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("c.txt"), std::string::npos) << e.what();
  }
  EXPECT_EQ(ReadTextFile(dir.path() / "keep.txt", "text"), "old");
  EXPECT_EQ(FilesIn(dir.path()), 1);
}

TEST(OutputBatch, OneFileTwiceIsRefused) {
  test::TempDir dir;
  OutputBatch batch;
  batch.Add(dir.path() / "a.txt", "1");
  test::ExpectInputError([&] { batch.Add(dir.path() / "a.txt", "2"); }, {"a.txt", "twice"});
}

}  // namespace
}  // namespace jgpm
