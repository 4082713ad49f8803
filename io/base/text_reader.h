// Line-oriented reading of text formats (ASF, AMC, BVH, splits) with the file:line of
// every error. Parsers take the whole text plus a source name so fuzz targets and tests
// can parse from memory exactly as from disk.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace jgpm {

// Reads a whole file. InputError when it is missing, a directory, unreadable, empty, or
// holds NUL bytes (a binary file given where text was expected). `what` names the
// expected content, e.g. "an ASF skeleton".
std::string ReadTextFile(const std::filesystem::path& path, const std::string& what);

// InputError when `path` is missing or a directory.
void CheckInputFile(const std::filesystem::path& path, const std::string& what);

// Writes `text` (any bytes) to `path` atomically (a temporary file of a name no other
// writer uses, in the same folder, then rename), so a failure never leaves a half-written
// or clobbered file and two writers never mix their bytes. InputError on failure.
void WriteFileAtomic(const std::filesystem::path& path, const std::string& text);
// The first half of WriteFileAtomic: `bytes` in a new temporary file beside `path`
// ("<path>.tmp-XXXXXX"), whose name is returned; the caller renames or removes it.
// InputError naming `path` when its folder does not exist, it is a folder, or the write
// fails (nothing is left behind then).
std::filesystem::path WriteTemporaryBeside(const std::filesystem::path& path, const std::string& bytes);

// Splits a line at blanks (spaces, tabs).
std::vector<std::string_view> SplitBlanks(std::string_view line);

// Iterates the lines of a text; '\r' before '\n' is dropped. Line numbers count from 1.
class LineReader {
 public:
  // `text` must outlive the reader.
  LineReader(std::string_view text, std::string source);

  // Advances to the next line; false at the end of the text.
  bool Next();
  std::string_view line() const { return line_; }
  int line_number() const { return line_number_; }
  const std::string& source() const { return source_; }
  // "source:line"; at the end of the text, "source:line" of the last line read.
  std::string Where() const;

  // Throws InputError("source:line: <what>").
  [[noreturn]] void Fail(const std::string& what) const;

  // Parses a finite number (NaN and inf are rejected). `what` names the value for errors.
  double ParseDouble(std::string_view token, const std::string& what) const;
  // Like ParseDouble, but also accepts "inf"/"-inf" (ASF limits).
  double ParseDoubleOrInf(std::string_view token, const std::string& what) const;
  int ParseInt(std::string_view token, const std::string& what) const;

 private:
  std::string_view text_;
  std::string source_;
  size_t pos_ = 0;
  std::string_view line_;
  int line_number_ = 0;
};

// Quotes a token for an error message, shortening long ones.
std::string Quote(std::string_view token);

// Formats a double with the fewest digits that read back to the same value.
std::string FormatShortest(double value);

}  // namespace jgpm
