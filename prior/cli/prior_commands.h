// Gait priors from the command line: `jgpm train`, `jgpm model info`, `jgpm plot latent`,
// `jgpm synth`; and the learning benchmarks `jgpm bench learning` (one objective evaluation
// and time to converge against N, exact and sparse) and `jgpm bench inducing` (how many
// inducing inputs a learned model's objective needs).
#pragma once

#include <CLI/CLI.hpp>

namespace jgpm::cli {

// Registers `train`, `model info`, `plot latent` and `synth` under `app`.
void AddPriorCommands(CLI::App& app);
// Registers `learning` and `inducing` under the `bench` command.
void AddPriorBenches(CLI::App* bench);

}  // namespace jgpm::cli
