// `jgpm data ...`: motion files and gait datasets.
#pragma once

#include <CLI/CLI.hpp>

namespace jgpm::cli {

// Registers `data info`, `data convert` and `data cycles` under `app`.
void AddDataCommands(CLI::App& app);

}  // namespace jgpm::cli
