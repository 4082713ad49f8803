// `jgpm track` and `jgpm bench track`.
#pragma once

#include <CLI/CLI.hpp>

namespace jgpm::cli {

void AddTrackCommands(CLI::App& app);

}  // namespace jgpm::cli
