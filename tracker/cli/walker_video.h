// `jgpm calibrate --walkers`'s reader: a video's frames through background subtraction
// (tracker/frames), or a synthetic clip's observed masks, and its walkers' head-foot points (tracker/frames/walker_points.h).
#pragma once

#include "calibration/cli/calibration_commands.h"

namespace jgpm::cli {

// InputError naming the file when the video cannot be read.
WalkerEvidence ReadWalkersFromVideo(const WalkerVideo& video);

}  // namespace jgpm::cli
