#include "tracker/run/pose_table_cache.h"

#include <filesystem>
#include <sstream>

#include "io/base/checksum.h"
#include "io/base/error.h"
#include "io/base/mapped_file.h"
#include "io/base/text_reader.h"

namespace jgpm {
namespace {

namespace fs = std::filesystem;

// The key a kept table must hold: "" when the model file cannot be read.
std::string Key(const std::string& model_path, const std::string& asf_path, const PoseTableOptions& options) {
  const MappedFile model(model_path);
  if (!model.ok() || model.bytes().empty()) return {};
  std::ostringstream key;
  key << "table " << PoseTable::kVersion << " model " << Checksum(model.bytes()) << " asf "
      << (asf_path.empty() ? "none" : Checksum(MappedFile(asf_path).bytes())) << " nodes " << options.phase_nodes
      << ' ' << options.nodes_per_gait << ' ' << options.scale_nodes << ' ' << options.latent_nodes << " margin "
      << options.latent_margin << " neighbours " << options.density_neighbours;
  return key.str();
}

}  // namespace

std::string PoseTableCachePath(const std::string& model_path) { return model_path + ".table"; }

std::unique_ptr<PoseTable> ReadKeptPoseTable(const std::string& model_path, const std::string& asf_path,
                                             const PoseTableOptions& options,
                                             const std::function<void(const std::string&)>& note) {
  const std::string key = Key(model_path, asf_path, options);
  const std::string path = PoseTableCachePath(model_path);
  std::error_code error;
  if (key.empty() || !fs::is_regular_file(path, error)) return nullptr;
  try {
    return PoseTable::Parse(MappedFile(path).bytes(), key, path);
  } catch (const InputError& e) {
    if (note) note(std::string(e.what()) + "; building it again");
    return nullptr;
  }
}

std::shared_ptr<const PoseTable> CachedPoseTable(const GaitModel& model, const std::string& model_path,
                                                 const std::string& asf_path, const PoseTableOptions& options,
                                                 const std::function<void(const std::string&)>& note,
                                                 std::unique_ptr<PoseTable> kept) {
  if (kept && kept->manifold() == model.HasManifold() &&
      kept->NumBones() == static_cast<int>(model.skeleton().bones.size()) &&
      kept->NumChannels() == model.NumChannels())
    return kept;
  auto table = std::make_shared<const PoseTable>(model, options);
  const std::string key = Key(model_path, asf_path, options);
  if (key.empty()) return table;
  try {
    WriteFileAtomic(PoseTableCachePath(model_path), table->Serialize(key));
  } catch (const InputError& e) {
    if (note) note(std::string("the pose table is not kept: ") + e.what());
  }
  return table;
}

std::shared_ptr<const PoseTable> CachedPoseTable(const GaitModel& model, const std::string& model_path,
                                                 const std::string& asf_path, const PoseTableOptions& options,
                                                 const std::function<void(const std::string&)>& note) {
  return CachedPoseTable(model, model_path, asf_path, options, note,
                         ReadKeptPoseTable(model_path, asf_path, options, note));
}

}  // namespace jgpm
