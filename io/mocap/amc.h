// Acclaim AMC motion files (`:FULLY-SPECIFIED`, `:DEGREES`), read against their ASF.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>

#include "io/mocap/motion.h"
#include "io/mocap/skeleton.h"

namespace jgpm {

// Parses AMC text for `skeleton`. Every frame must list every bone that has dofs exactly
// once with one value per dof; frame numbers must be consecutive. Throws InputError
// naming source:line and what was expected.
Motion ParseAmc(std::string_view text, const std::string& source, const Skeleton& skeleton);
Motion ReadAmc(const std::filesystem::path& path, const Skeleton& skeleton);

// Formats AMC text. Numbers are written with the fewest digits that read back to the same
// double, so ParseAmc(FormatAmc(m)) reproduces m.values exactly.
std::string FormatAmc(const Motion& motion, const Skeleton& skeleton);
void WriteAmc(const std::filesystem::path& path, const Motion& motion, const Skeleton& skeleton);

}  // namespace jgpm
