// libFuzzer target: PoseTable::Parse (the table kept beside a model, MODEL.table) must
// return null (another key), throw InputError, or give a table that serialises back to
// the same bytes and looks up finite joints anywhere.
#include <cstddef>
#include <cstdint>
#include <string>

#include "io/base/error.h"
#include "tracker/state/pose_table.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string bytes(reinterpret_cast<const char*>(data), size);
  try {
    const std::unique_ptr<jgpm::PoseTable> table = jgpm::PoseTable::Parse(bytes, "fuzz", "fuzz.table");
    if (!table) return 0;
    JGPM_CHECK(table->Serialize("fuzz") == bytes);
    Eigen::Matrix3Xd joints;
    double foot = 0, density = 0;
    table->Lookup(Eigen::Vector3d(0.3, 0.7, 1.1), &joints, &foot, &density);
    JGPM_CHECK(joints.allFinite() && std::isfinite(foot) && std::isfinite(density));
    JGPM_CHECK(table->Pose(Eigen::Vector3d(-5, 50, 0)).allFinite());
    if (table->manifold()) JGPM_CHECK(std::isfinite(table->StrideMm(0.5, 1.0)));
  } catch (const jgpm::InputError&) {
  }
  return 0;
}
