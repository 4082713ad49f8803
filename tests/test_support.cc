#include "test_support.h"

#include "io/gait/data_root.h"

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <random>
#include <sstream>

#include <sys/wait.h>
#include <unistd.h>

namespace jgpm::test {
namespace fs = std::filesystem;

const fs::path& CmuRoot() {
  static const fs::path root = [] {
    std::vector<fs::path> tried;
    if (const char* env = std::getenv("JGPM_DATA"); env && *env) tried.emplace_back(env);
    tried.emplace_back(fs::path(JGPM_SOURCE_DIR) / "data" / "cmu");
    tried.emplace_back(fs::path(JGPM_SOURCE_DIR) / ".." / "shared" / "data" / "cmu");
    for (const fs::path& candidate : tried) {
      if (HoldsMotionData(candidate)) return fs::canonical(candidate);  // as jgpm decides
    }
    std::cerr << "test data missing: no CMU data root (tried $JGPM_DATA, "
              << tried[tried.size() - 2] << ", " << tried.back() << ")\n";
    std::exit(1);
  }();
  return root;
}

std::vector<TrialId> SplitTrials(const std::string& name) {
  return ReadSplit(fs::path(JGPM_SPLITS_DIR) / (name + ".txt"));
}

std::vector<CmuTrial> AllCmuTrials() {
  std::vector<CmuTrial> trials;
  for (const auto& subject : fs::directory_iterator(CmuRoot() / "subjects")) {
    const fs::path asf = subject.path() / (subject.path().filename().string() + ".asf");
    for (const auto& file : fs::directory_iterator(subject.path())) {
      if (file.path().extension() == ".amc") trials.push_back({asf, file.path()});
    }
  }
  std::sort(trials.begin(), trials.end(),
            [](const CmuTrial& a, const CmuTrial& b) { return a.amc < b.amc; });
  return trials;
}

TempDir::TempDir() {
  static std::atomic<int> counter{0};
  std::random_device random;
  path_ = fs::temp_directory_path() /
          ("jgpm_test_" + std::to_string(getpid()) + "_" + std::to_string(counter++) + "_" +
           std::to_string(random()));
  fs::create_directories(path_);
}

TempDir::~TempDir() {
  std::error_code ec;
  fs::permissions(path_, fs::perms::owner_all, fs::perm_options::add, ec);
  fs::remove_all(path_, ec);
}

fs::path TempDir::Write(const std::string& name, const std::string& text) const {
  const fs::path file = path_ / name;
  std::ofstream(file, std::ios::binary) << text;
  return file;
}

int LineOf(const std::string& text, const std::string& needle) {
  const size_t at = text.find(needle);
  if (at == std::string::npos) return 0;
  return 1 + static_cast<int>(std::count(text.begin(), text.begin() + at, '\n'));
}

std::string Replace(std::string text, const std::string& from, const std::string& to) {
  const size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << "test bug: '" << from << "' not in the text";
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

int RunCommand(const std::string& command, std::string* out, std::string* err) {
  const TempDir dir;
  const fs::path out_file = dir.path() / "stdout", err_file = dir.path() / "stderr";
  const std::string full = command + " >" + out_file.string() + " 2>" + err_file.string();
  const int status = std::system(full.c_str());
  auto slurp = [](const fs::path& p) {
    std::ifstream in(p);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
  };
  *out = slurp(out_file);
  *err = slurp(err_file);
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128;
}

CommandResult RunJgpm(const std::string& arguments) {
  CommandResult r;
  r.status = RunCommand(std::string(JGPM_BINARY) + " " + arguments, &r.out, &r.err);
  return r;
}

}  // namespace jgpm::test
