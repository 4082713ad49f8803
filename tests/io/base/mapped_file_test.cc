// A mapped file holds the file's bytes exactly (binary, with zeros); a missing file or a
// folder is not ok; an empty file is ok and empty.
#include "io/base/mapped_file.h"

#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "test_support.h"

namespace jgpm {
namespace {

namespace fs = std::filesystem;

TEST(MappedFile, HoldsTheBytesOrSaysItCannot) {
  test::TempDir dir;
  std::string bytes;
  for (int i = 0; i < 3 * 4096 + 17; ++i) bytes.push_back(static_cast<char>((i * 7919) % 256));
  const fs::path path = dir.path() / "a.bin";
  std::ofstream(path, std::ios::binary).write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  {
    const MappedFile mapped(path.string());
    ASSERT_TRUE(mapped.ok());
    EXPECT_EQ(mapped.bytes(), bytes);
  }
  const MappedFile missing((dir.path() / "none.bin").string());
  EXPECT_FALSE(missing.ok());
  EXPECT_TRUE(missing.bytes().empty());
  const MappedFile folder(dir.path().string());
  EXPECT_FALSE(folder.ok());
  std::ofstream(dir.path() / "empty.bin").close();
  const MappedFile empty((dir.path() / "empty.bin").string());
  EXPECT_TRUE(empty.ok());
  EXPECT_TRUE(empty.bytes().empty());
}

}  // namespace
}  // namespace jgpm
