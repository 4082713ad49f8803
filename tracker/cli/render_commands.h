// `jgpm render`: synthetic silhouette clips from motion capture (tracker/clip/synthetic_clip.h).
#pragma once

#include <CLI/CLI.hpp>

namespace jgpm::cli {

void AddRenderCommands(CLI::App& app);

}  // namespace jgpm::cli
