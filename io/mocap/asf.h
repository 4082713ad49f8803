// Acclaim ASF skeleton files (the CMU motion-capture skeletons).
#pragma once

#include <filesystem>
#include <string>
#include <string_view>

#include "io/mocap/skeleton.h"

namespace jgpm {

// Parses ASF text. `source` names it in errors ("file:line: what was expected").
// Bones are returned parents-first (depth-first from the root, children in hierarchy
// order), which for CMU files is the file's own order. Angles in the result are degrees
// even when the file says `angle rad`. Throws InputError on any malformed input.
Skeleton ParseAsf(std::string_view text, const std::string& source);

Skeleton ReadAsf(const std::filesystem::path& path);

}  // namespace jgpm
