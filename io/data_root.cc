#include "io/data_root.h"

#include <cstdlib>
#include <system_error>

#include "io/error.h"

namespace jgpm {
namespace fs = std::filesystem;
namespace {

bool HoldsData(const fs::path& root) {
  std::error_code ec;
  return fs::is_directory(root / "subjects", ec);
}

}  // namespace

fs::path ResolveDataRoot(const std::optional<std::string>& flag) {
  const std::string hint =
      " (expected a CMU layout folder with subjects/NN/NN.asf; datasets_scripts/fetch_cmu.sh "
      "downloads one into ./data/cmu)";
  if (flag) {
    if (!HoldsData(*flag)) ThrowInputError("--data " + *flag, "holds no subjects/ folder" + hint);
    return fs::path(*flag);
  }
  if (const char* env = std::getenv("JGPM_DATA"); env != nullptr && *env != '\0') {
    if (!HoldsData(env)) {
      ThrowInputError("$JGPM_DATA=" + std::string(env), "holds no subjects/ folder" + hint);
    }
    return fs::path(env);
  }
  const fs::path candidates[] = {"data/cmu", "../shared/data/cmu"};
  for (const fs::path& candidate : candidates) {
    if (HoldsData(candidate)) return candidate;
  }
  ThrowInputError("", "no motion-capture data found; tried --data (not given), $JGPM_DATA (not "
                      "set), ./data/cmu, ../shared/data/cmu" + hint);
}

}  // namespace jgpm
