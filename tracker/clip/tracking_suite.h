// The tracking benchmark's clips (datasets_scripts/tracking_suite.txt): one clip a line,
// `NAME TRIAL [jgpm render options]`, '#' comments. TRIAL may be several joined by '+'
// (07_01+35_10: several walkers, datasets_scripts/crowd_suite.txt), each placed by a
// --walk (one per trial, or none). Rendering the suite makes each clip folder that is not
// there yet.
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "io/gait/split.h"
#include "tracker/clip/synthetic_clip.h"

namespace jgpm {

struct SuiteClip {
  std::string name;      // e.g. "07_01-4cam"
  TrialId trial;         // e.g. 07_01: the (first) walker's
  std::vector<TrialId> others;         // the other walkers' trials, in order
  std::vector<ClipPlacement> walks;    // --walk: none, or one per walker
  ClipOptions options;   // the line's render options over the defaults
  std::string options_text;
};

// InputError naming the file and line for a malformed line, an unknown or bad option, a
// repeated name. Options understood (as `jgpm render` has them): --cameras --width
// --height --fps --max-frames --ring-radius --ring-height --sensor-noise --mask-noise --holes --clutter
// --lighting --drop-rate --width-scale --seed --rig --body-seed --clothing --bag --shadow --reflection
// --occluders --calibration-error --pause --walk (--bag and --shadow take no value; --walk
// once per walker; --pause as often as the walkers stop).
std::vector<SuiteClip> ParseTrackingSuite(const std::string& text, const std::string& source);
std::vector<SuiteClip> ReadTrackingSuite(const std::filesystem::path& path);

// Renders each clip into `folder`/NAME from the trial under the data root (asked of
// `data_root` only when a clip must be rendered), unless NAME/ground_truth.json is there
// already. `progress` (may be empty) gets each clip and whether it was rendered (false:
// reused).
void RenderTrackingSuite(const std::vector<SuiteClip>& clips, const std::function<std::filesystem::path()>& data_root,
                         const std::filesystem::path& folder,
                         const std::function<void(const SuiteClip&, bool rendered)>& progress = {});

}  // namespace jgpm
