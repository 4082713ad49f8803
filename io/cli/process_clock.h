// How long this process has run, from the moment the system started it.
//
// A command's own clock starts in main, after the dynamic loader has mapped and relocated
// its libraries: OpenCV's video and image I/O bring about 240 shared objects (FFmpeg,
// GStreamer, GDAL), 0.2 s on our machines before main runs. A summary that says how long a
// run took counts that too.
#pragma once

#include <optional>

namespace jgpm {

// Seconds since the kernel started this process (Linux: /proc/self/stat's start time
// against CLOCK_BOOTTIME, both since boot; 10 ms steps), or nothing where they cannot be
// read.
std::optional<double> SecondsSinceProcessStarted();

}  // namespace jgpm
