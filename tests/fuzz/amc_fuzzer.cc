// libFuzzer target: ParseAmc against a fixed small skeleton must either return a motion
// that writes and reads back exactly, or throw InputError.
#include <cstddef>
#include <cstdint>
#include <string>

#include "io/base/error.h"
#include "io/mocap/amc.h"
#include "io/mocap/asf.h"
#include "small_asf.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const jgpm::Skeleton skeleton = jgpm::ParseAsf(jgpm::test::SmallAsfText(), "small.asf");
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const jgpm::Motion motion = jgpm::ParseAmc(text, "fuzz.amc", skeleton);
    const jgpm::Motion back = jgpm::ParseAmc(jgpm::FormatAmc(motion, skeleton), "back.amc", skeleton);
    JGPM_CHECK((back.values.array() == motion.values.array()).all());
  } catch (const jgpm::InputError&) {
  }
  return 0;
}
