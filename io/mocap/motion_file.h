// Whole motion files, whatever their format: what `jgpm data info` and `jgpm data convert`
// do, as library calls.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

namespace jgpm {

enum class MotionFormat { kAsf, kAmc, kBvh };

// From the extension (case-insensitive); InputError naming `what` (e.g. the option) for
// any other extension.
MotionFormat FormatFromPath(const std::filesystem::path& path, const std::string& what);

struct MotionFileOptions {
  // Skeleton for AMC files. When absent, an AMC's CMU-layout sibling NN.asf is used.
  std::optional<std::filesystem::path> asf;
  // AMC files do not store their rate; CMU's is 120.
  double amc_frames_per_second = 120.0;
  // BVH files do not store their unit; ours are in centimetres.
  double bvh_mm_per_unit = 10.0;
};

// The skeleton of an AMC file: options.asf, else X.asf next to X.amc, else NN.asf next to
// NN_TT.amc (CMU). InputError when none exists.
std::filesystem::path SkeletonForAmc(const std::filesystem::path& amc,
                                     const MotionFileOptions& options);

// A human-readable summary: frames, rate, duration, joints and channels (plus bones for an
// ASF and the root's travel for motions).
std::string DescribeMotionFile(const std::filesystem::path& path, const MotionFileOptions& options);

// Converts AMC or BVH `in` to AMC or BVH `out` for the skeleton options.asf (needed for
// AMC output, and for AMC input unless found next to it). The output is written only when
// the whole conversion succeeded; `out` may not be `in`. Returns a one-line summary.
std::string ConvertMotionFile(const std::filesystem::path& in, const std::filesystem::path& out,
                              const MotionFileOptions& options);

}  // namespace jgpm
