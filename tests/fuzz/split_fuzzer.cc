// libFuzzer target: ParseSplit must either return distinct, well-formed trial ids or throw
// InputError. Splits have no writer; the ids written one per line (the format's plainest
// form) must parse back to the same ids.
#include <cstddef>
#include <cstdint>
#include <set>
#include <string>
#include <string_view>

#include "io/base/error.h"
#include "io/gait/split.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    const std::vector<jgpm::TrialId> ids = jgpm::ParseSplit(text, "fuzz.txt");
    JGPM_CHECK(!ids.empty());
    std::set<std::string> names;
    std::string written;
    for (const jgpm::TrialId& id : ids) {
      jgpm::TrialId again;
      JGPM_CHECK(jgpm::ParseTrialId(id.name, &again) && again.subject == id.subject);
      JGPM_CHECK(names.insert(id.name).second);
      written += id.name + "\n";
    }
    const std::vector<jgpm::TrialId> back = jgpm::ParseSplit(written, "back.txt");
    JGPM_CHECK(back.size() == ids.size());
    for (size_t i = 0; i < ids.size(); ++i) {
      JGPM_CHECK(back[i].name == ids[i].name && back[i].subject == ids[i].subject);
    }
  } catch (const jgpm::InputError&) {
  }
  return 0;
}
