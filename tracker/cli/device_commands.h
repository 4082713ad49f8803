// `jgpm devices`: the V4L2 cameras present, and what they can give.
#pragma once

#include <CLI/CLI.hpp>

namespace jgpm::cli {

void AddDeviceCommands(CLI::App& app);

}  // namespace jgpm::cli
