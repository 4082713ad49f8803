// `jgpm eval`: the paper's validation of gait priors, one case or the whole suite.
#pragma once

#include <CLI/CLI.hpp>

namespace jgpm::cli {

void AddValidationCommands(CLI::App& app);

}  // namespace jgpm::cli
