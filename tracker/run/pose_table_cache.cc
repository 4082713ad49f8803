#include "tracker/run/pose_table_cache.h"

#include <filesystem>
#include <fstream>
#include <sstream>

#include "io/base/checksum.h"
#include "io/base/error.h"
#include "io/base/text_reader.h"

namespace jgpm {
namespace {

namespace fs = std::filesystem;

// A file's bytes, or "" when it cannot be read. Read straight into a string of the file's
// size: a table is tens of MB, and a stream's growing buffer copied it three times.
std::string ReadBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in) return {};
  std::string bytes(static_cast<size_t>(in.tellg()), '\0');
  in.seekg(0);
  return in.read(bytes.data(), static_cast<std::streamsize>(bytes.size())) ? bytes : std::string();
}

}  // namespace

std::string PoseTableCachePath(const std::string& model_path) { return model_path + ".table"; }

std::shared_ptr<const PoseTable> CachedPoseTable(const GaitModel& model, const std::string& model_path,
                                                 const std::string& asf_path, const PoseTableOptions& options,
                                                 const std::function<void(const std::string&)>& note) {
  const auto say = [&note](const std::string& text) {
    if (note) note(text);
  };
  const std::string model_bytes = ReadBytes(model_path);
  if (model_bytes.empty()) return std::make_shared<const PoseTable>(model, options);
  std::ostringstream key;
  key << "table " << PoseTable::kVersion << " model " << Checksum(model_bytes) << " asf " << (asf_path.empty() ? "none" : Checksum(ReadBytes(asf_path)))
      << " nodes " << options.phase_nodes << ' ' << options.nodes_per_gait << ' ' << options.scale_nodes << ' '
      << options.latent_nodes << " margin " << options.latent_margin << " neighbours " << options.density_neighbours;
  const std::string path = PoseTableCachePath(model_path);
  std::error_code error;
  if (fs::is_regular_file(path, error)) {
    try {
      std::unique_ptr<PoseTable> kept = PoseTable::Parse(ReadBytes(path), key.str(), path);
      if (kept && kept->manifold() == model.HasManifold() &&
          kept->NumBones() == static_cast<int>(model.skeleton().bones.size()) &&
          kept->NumChannels() == model.NumChannels())
        return kept;
    } catch (const InputError& e) {
      say(std::string(e.what()) + "; building it again");
    }
  }
  auto table = std::make_shared<const PoseTable>(model, options);
  try {
    WriteFileAtomic(path, table->Serialize(key.str()));
  } catch (const InputError& e) {
    say(std::string("the pose table is not kept: ") + e.what());
  }
  return table;
}

}  // namespace jgpm
