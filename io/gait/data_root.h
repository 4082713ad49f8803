// Where the CMU motion-capture data lives (CMU layout: <root>/subjects/NN/NN.asf and
// NN_TT.amc).
#pragma once

#include <filesystem>
#include <optional>
#include <string>

namespace jgpm {

// The data root: `flag` (the --data option) if given, else $JGPM_DATA if set; each of those
// must hold data, since the user asked for it. Otherwise the first of ./data/cmu and
// ../shared/data/cmu that holds data. A folder holds data when its subjects/ folder holds
// a subject folder with an .asf skeleton, so an empty or half-made ./data/cmu is skipped.
// InputError listing every place tried when none does.
std::filesystem::path ResolveDataRoot(const std::optional<std::string>& flag);

// Whether `root` holds data in that sense.
bool HoldsMotionData(const std::filesystem::path& root);

}  // namespace jgpm
