// `jgpm devices`: the V4L2 cameras present, and what they can give. `jgpm capture`: frames
// of a camera saved as images (chessboard shots for `jgpm calibrate`, the floor board
// that places the camera, an empty-scene picture for `jgpm track --background`).
#pragma once

#include <string>

#include <CLI/CLI.hpp>

namespace jgpm::cli {

// A camera's `--size`: "640x480" -> 640, 480; InputError naming the option otherwise.
void ParseSizeOption(const std::string& text, int* width, int* height);

void AddDeviceCommands(CLI::App& app);

}  // namespace jgpm::cli
