// `jgpm train` and `jgpm plot latent`: gait priors.
#pragma once

#include <CLI/CLI.hpp>

namespace jgpm::cli {

void AddPriorCommands(CLI::App& app);

}  // namespace jgpm::cli
