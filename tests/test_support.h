// Shared helpers for the test suites: where the CMU data is, temporary folders, small
// synthetic skeletons written by the tests themselves.
#pragma once

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "io/base/error.h"
#include "io/gait/split.h"
#include "io/mocap/skeleton.h"
#include "small_asf.h"

namespace jgpm::test {

// The CMU data root: $JGPM_DATA, else <source>/data/cmu, else <source>/../shared/data/cmu.
// Aborts the test program with a clear message when none exists: tests that need real data
// must not pass silently without it.
const std::filesystem::path& CmuRoot();

// Trial ids of a named split in datasets_scripts/splits.
std::vector<TrialId> SplitTrials(const std::string& name);

// Every AMC under CmuRoot(), sorted, with its ASF.
struct CmuTrial {
  std::filesystem::path asf;
  std::filesystem::path amc;
};
std::vector<CmuTrial> AllCmuTrials();

// A fresh, empty folder removed when the object is destroyed.
class TempDir {
 public:
  TempDir();
  ~TempDir();
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const std::filesystem::path& path() const { return path_; }
  // Writes `text` to path()/name and returns the full path.
  std::filesystem::path Write(const std::string& name, const std::string& text) const;

 private:
  std::filesystem::path path_;
};


// Runs `f` and expects an InputError whose message contains every one of `parts`.
template <typename F>
void ExpectInputError(F f, std::initializer_list<std::string> parts) {
  try {
    f();
    ADD_FAILURE() << "expected an InputError";
  } catch (const InputError& e) {
    for (const std::string& part : parts) {
      EXPECT_NE(std::string(e.what()).find(part), std::string::npos)
          << "message: " << e.what() << "\nlacks: " << part;
    }
  }
}

// Lines in `text` (its newlines): a one-line error is "...\n".
inline int CountLines(const std::string& text) { return static_cast<int>(std::count(text.begin(), text.end(), '\n')); }

// 1-based number of the first line of `text` containing `needle`, or 0.
int LineOf(const std::string& text, const std::string& needle);

// `text` with the first occurrence of `from` replaced by `to` (fails the test if absent).
std::string Replace(std::string text, const std::string& from, const std::string& to);

// A malformed-input case: `from` -> `to` in a valid text; the error must name the line
// holding `line_needle` in the mutated text (0: no line check) and contain `phrase`.
struct MalformedCase {
  std::string name;
  std::string from;
  std::string to;
  std::string line_needle;
  std::string phrase;
};
// Applies the case to `valid_text` and expects `parse(text, source)` to fail as described.
template <typename Parse>
void ExpectMalformed(const MalformedCase& c, const std::string& valid_text,
                     const std::string& source, Parse parse) {
  const std::string text = Replace(valid_text, c.from, c.to);
  std::string where = source;
  if (!c.line_needle.empty()) where += ":" + std::to_string(LineOf(text, c.line_needle));
  ExpectInputError([&] { parse(text, source); }, {where, c.phrase});
}
inline void PrintTo(const MalformedCase& c, std::ostream* os) { *os << c.name; }
inline std::string CaseName(const testing::TestParamInfo<MalformedCase>& info) {
  return info.param.name;
}

// Runs a shell command; returns its exit status and fills stdout/stderr text.
int RunCommand(const std::string& command, std::string* out, std::string* err);

// The `jgpm` binary (JGPM_BINARY) run with `arguments`.
struct CommandResult {
  int status = 0;
  std::string out;
  std::string err;
};
CommandResult RunJgpm(const std::string& arguments);

}  // namespace jgpm::test
