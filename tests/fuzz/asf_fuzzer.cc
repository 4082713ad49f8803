// libFuzzer target: ParseAsf must either return a usable skeleton or throw InputError.
#include <cstddef>
#include <cstdint>
#include <string>

#include "io/base/error.h"
#include "io/mocap/asf.h"
#include "io/mocap/kinematics.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const jgpm::Skeleton skeleton = jgpm::ParseAsf(text, "fuzz.asf");
    // A parsed skeleton must be usable: parents first, FK of the rest pose runs.
    for (size_t b = 1; b < skeleton.bones.size(); ++b) {
      JGPM_CHECK(skeleton.bones[b].parent >= 0 && skeleton.bones[b].parent < static_cast<int>(b));
    }
    const std::vector<double> rest(skeleton.NumChannels(), 0.0);
    jgpm::Kinematics(skeleton).Compute(rest.data());
  } catch (const jgpm::InputError&) {
  }
  return 0;
}
