// `jgpm calibrate`: a camera's intrinsics from chessboard images and, optionally, its
// place in the world (from a chessboard on the floor or a pose file), as camera YAML.
#pragma once

#include <CLI/CLI.hpp>

namespace jgpm::cli {

// Registers `calibrate` under `app`.
void AddCalibrationCommands(CLI::App& app);

}  // namespace jgpm::cli
