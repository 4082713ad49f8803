// `jgpm transition`: the motion between two recorded motions (LSOPA and its baselines).
#pragma once

#include <CLI/CLI.hpp>

namespace jgpm::cli {

void AddTransitionCommands(CLI::App& app);

}  // namespace jgpm::cli
