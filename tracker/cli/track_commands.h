// `jgpm track` (a person's 3-D pose in a clip, video files, an image folder or a live
// camera) and `jgpm bench track` (the tracking suite with every model and the baselines).
#pragma once

#include <CLI/CLI.hpp>

namespace jgpm::cli {

// Registers `track` under `app`.
void AddTrackCommands(CLI::App& app);
// Registers `track` under the `bench` command.
void AddTrackBench(CLI::App* bench);

}  // namespace jgpm::cli
