// `jgpm devices`: the V4L2 cameras present, and what they can give. `jgpm capture`: frames
// of a camera saved as images (chessboard shots for `jgpm calibrate`, the floor board
// that places the camera, an empty-scene picture for `jgpm track --background`).
#pragma once

#include <CLI/CLI.hpp>

namespace jgpm::cli {

void AddDeviceCommands(CLI::App& app);

}  // namespace jgpm::cli
