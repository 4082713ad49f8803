// libFuzzer target: ParseCameraYaml must either return a valid camera or throw
// InputError (OpenCV's own YAML parser underneath included), and what parses must write
// and read back to the same camera.
#include <cstddef>
#include <cstdint>
#include <string>

#include "calibration/camera.h"
#include "io/base/error.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const jgpm::CameraFile file = jgpm::ParseCameraYaml(text, "fuzz.yaml");
    std::string why;
    JGPM_CHECK(file.camera.Check(&why));
    const jgpm::CameraFile again = jgpm::ParseCameraYaml(jgpm::FormatCameraYaml(file), "again.yaml");
    JGPM_CHECK(again.camera.fx == file.camera.fx && again.camera.distortion == file.camera.distortion &&
               again.camera.cam_from_world_rotation == file.camera.cam_from_world_rotation);
  } catch (const jgpm::InputError&) {
  }
  return 0;
}
