// Model files: one self-describing, versioned JSON file holding everything a trained gait
// model needs (kind, options, training poses, channel means and scales, latent points,
// hyper-parameters, topology, training trial ids, the reference skeleton's ASF text and
// the training summary), with a checksum of its content.
#pragma once

#include <filesystem>
#include <memory>
#include <string>

#include "prior/model/gait_model.h"

namespace jgpm {

constexpr int kModelFileVersion = 1;

std::string FormatModelFile(const GaitModelData& data);
void WriteModelFile(const std::filesystem::path& path, const GaitModel& model);

// InputError naming the file for: not JSON or truncated, another format or version, a
// checksum that does not match the content (edited or corrupted), missing or mistyped
// fields, inconsistent sizes.
std::unique_ptr<GaitModel> ParseModelFile(const std::string& text, const std::string& source);
std::unique_ptr<GaitModel> ReadModelFile(const std::filesystem::path& path);

}  // namespace jgpm
