// libFuzzer target: ParseBvh must either return a motion that writes and reads back
// exactly (and whose forward kinematics runs), or throw InputError.
#include <cstddef>
#include <cstdint>
#include <string>

#include "io/base/error.h"
#include "io/mocap/bvh.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const jgpm::Bvh bvh = jgpm::ParseBvh(text, "fuzz.bvh");
    const jgpm::Bvh back = jgpm::ParseBvh(jgpm::FormatBvh(bvh), "back.bvh");
    JGPM_CHECK(back.joints.size() == bvh.joints.size());
    JGPM_CHECK((back.frames.array() == bvh.frames.array()).all());
    Eigen::Matrix3Xd joints;
    jgpm::ComputeBvhPose(bvh, 0, &joints);
  } catch (const jgpm::InputError&) {
  }
  return 0;
}
