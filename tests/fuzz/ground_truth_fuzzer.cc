// libFuzzer target: ParseGroundTruth (a synthetic clip's ground_truth.json) must either
// return a ground truth whose parts agree or throw InputError; what parses must format and
// parse back to the same text.
#include <cstddef>
#include <cstdint>
#include <string>

#include "io/base/error.h"
#include "tracker/clip/clip_format.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const jgpm::ClipGroundTruth truth = jgpm::ParseGroundTruth(text, "fuzz.json");
    for (const jgpm::ClipFrame& f : truth.frames) {
      JGPM_CHECK(f.joints_mm.cols() == static_cast<int>(truth.joint_names.size()) && f.joints_mm.allFinite());
    }
    const std::string formatted = jgpm::FormatGroundTruth(truth);
    JGPM_CHECK(jgpm::FormatGroundTruth(jgpm::ParseGroundTruth(formatted, "again.json")) == formatted);
  } catch (const jgpm::InputError&) {
  }
  return 0;
}
