// libFuzzer target: ParseTrackingSuite must either return well-formed clips (a safe name,
// a trial id, render options that pass their Check) or throw InputError.
#include <cstddef>
#include <cstdint>
#include <string>

#include "io/base/error.h"
#include "tracker/clip/tracking_suite.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    for (const jgpm::SuiteClip& clip : jgpm::ParseTrackingSuite(text, "fuzz.txt")) {
      JGPM_CHECK(!clip.name.empty() && clip.name[0] != '.' && clip.name.find('/') == std::string::npos);
      JGPM_CHECK(clip.options.Check(nullptr));
    }
  } catch (const jgpm::InputError&) {
  }
  return 0;
}
