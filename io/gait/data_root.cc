#include "io/gait/data_root.h"

#include <cstdlib>
#include <system_error>

#include "io/base/error.h"

namespace jgpm {
namespace fs = std::filesystem;
namespace {

// How a default place that was tried is listed when none holds data.
std::string Tried(const fs::path& candidate, const std::string& shown) {
  std::error_code ec;
  return fs::exists(candidate, ec) ? shown + " (exists, no subjects/NN/NN.asf)" : shown;
}

}  // namespace

// True when root/subjects/ holds a subject folder with an .asf skeleton. A bare subjects/
// folder (an empty or interrupted download) is not data, so it cannot shadow the places
// searched after it.
bool HoldsMotionData(const fs::path& root) {
  std::error_code ec;
  for (fs::directory_iterator subject(root / "subjects", ec), end; !ec && subject != end;
       subject.increment(ec)) {
    std::error_code file_ec;
    if (!subject->is_directory(file_ec)) continue;
    for (fs::directory_iterator file(subject->path(), file_ec); !file_ec && file != end;
         file.increment(file_ec)) {
      if (file->path().extension() == ".asf" && file->is_regular_file(file_ec)) return true;
    }
  }
  return false;
}


fs::path ResolveDataRoot(const std::optional<std::string>& flag) {
  const std::string hint =
      " (expected a CMU layout folder with subjects/NN/NN.asf; datasets_scripts/fetch_cmu.sh "
      "downloads one into ./data/cmu)";
  const std::string refused = "holds no subjects/NN/ folder with an .asf skeleton" + hint;
  if (flag) {
    if (!HoldsMotionData(*flag)) ThrowInputError("--data " + *flag, refused);
    return fs::path(*flag);
  }
  if (const char* env = std::getenv("JGPM_DATA"); env != nullptr && *env != '\0') {
    if (!HoldsMotionData(env)) {
      ThrowInputError("$JGPM_DATA=" + std::string(env), refused);
    }
    return fs::path(env);
  }
  const fs::path candidates[] = {"data/cmu", "../shared/data/cmu"};
  for (const fs::path& candidate : candidates) {
    if (HoldsMotionData(candidate)) return candidate;
  }
  ThrowInputError("", "no motion-capture data found; tried --data (not given), $JGPM_DATA (not "
                      "set), " + Tried(candidates[0], "./data/cmu") + ", " +
                      Tried(candidates[1], "../shared/data/cmu") + hint);
}

}  // namespace jgpm
