// `jgpm train`, `jgpm plot latent`, `jgpm bench learning`: gait priors.
#pragma once

#include <CLI/CLI.hpp>

namespace jgpm::cli {

void AddPriorCommands(CLI::App& app);
// `jgpm bench learning`, under the `bench` command.
void AddBenchLearning(CLI::App* bench);

}  // namespace jgpm::cli
