#include "tracker/clip/tracking_suite.h"

#include <set>
#include <system_error>

#include "io/base/error.h"
#include "io/base/text_reader.h"
#include "io/mocap/amc.h"
#include "io/mocap/asf.h"

namespace jgpm {
namespace fs = std::filesystem;

std::vector<SuiteClip> ParseTrackingSuite(const std::string& text, const std::string& source) {
  LineReader in(text, source);
  std::vector<SuiteClip> clips;
  std::set<std::string> names;
  while (in.Next()) {
    std::string_view line = in.line();
    if (const size_t hash = line.find('#'); hash != std::string_view::npos) line = line.substr(0, hash);
    const std::vector<std::string_view> tokens = SplitBlanks(line);
    if (tokens.empty()) continue;
    if (tokens.size() < 2) in.Fail("expected NAME TRIAL [render options]");
    SuiteClip clip;
    clip.name = std::string(tokens[0]);
    if (clip.name.find_first_not_of("ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789_-.") !=
            std::string::npos ||
        clip.name[0] == '.') {
      in.Fail("a clip name may hold only letters, digits, '_', '-' and '.', found " + Quote(tokens[0]));
    }
    if (!names.insert(clip.name).second) in.Fail("clip " + Quote(tokens[0]) + " named twice");
    std::vector<std::string_view> trials;
    for (std::string_view rest = tokens[1];;) {
      const size_t plus = rest.find('+');
      trials.push_back(rest.substr(0, plus));
      if (plus == std::string_view::npos) break;
      rest = rest.substr(plus + 1);
    }
    if (trials.size() > 8) in.Fail("at most 8 walkers, found " + std::to_string(trials.size()));
    for (size_t w = 0; w < trials.size(); ++w) {
      TrialId id;
      if (!ParseTrialId(std::string(trials[w]), &id))
        in.Fail("expected a trial id such as 07_01 (or several joined by '+'), found " + Quote(tokens[1]));
      if (w == 0) clip.trial = id;
      else clip.others.push_back(id);
    }
    ClipOptions& o = clip.options;
    for (size_t i = 2; i < tokens.size(); i += 2) {
      const std::string option(tokens[i]);
      if (option == "--bag" || option == "--shadow") {  // flags
        (option == "--bag" ? o.body.bag : o.scene.shadow) = true;
        clip.options_text += (clip.options_text.empty() ? "" : " ") + option;
        --i;
        continue;
      }
      if (i + 1 >= tokens.size()) in.Fail("option " + option + " needs a value");
      const std::string_view value = tokens[i + 1];
      const std::string what = "the value of " + option;
      if (option == "--cameras") o.rig.num_cameras = in.ParseInt(value, what);
      else if (option == "--width") o.rig.width = in.ParseInt(value, what);
      else if (option == "--height") o.rig.height = in.ParseInt(value, what);
      else if (option == "--ring-radius") o.rig.ring_radius_mm = in.ParseDouble(value, what);
      else if (option == "--ring-height") o.rig.camera_height_mm = in.ParseDouble(value, what);
      else if (option == "--fps") o.fps = in.ParseDouble(value, what);
      else if (option == "--max-frames") o.max_frames = in.ParseInt(value, what);
      else if (option == "--sensor-noise") o.degradations.sensor_noise = in.ParseDouble(value, what);
      else if (option == "--mask-noise") o.degradations.mask_noise_px = in.ParseDouble(value, what);
      else if (option == "--holes") o.degradations.holes = in.ParseInt(value, what);
      else if (option == "--clutter") o.degradations.clutter_blobs = in.ParseInt(value, what);
      else if (option == "--lighting") o.degradations.lighting_gain = in.ParseDouble(value, what);
      else if (option == "--drop-rate") o.degradations.drop_rate = in.ParseDouble(value, what);
      else if (option == "--reflection") o.scene.reflection = in.ParseDouble(value, what);
      else if (option == "--width-scale") o.body.width_scale = in.ParseDouble(value, what);
      else if (option == "--body-seed") o.body.body_seed = static_cast<uint64_t>(in.ParseInt(value, what));
      else if (option == "--clothing") {
        if (!ParseClothing(value, &o.body.clothing)) in.Fail(what + ": expected none, trousers, coat or skirt");
      } else if (option == "--rig") {
        if (!ParseRigKind(value, &o.rig.kind)) in.Fail(what + ": expected ring, surveillance or webcam");
      } else if (option == "--occluders") o.scene.occluders = in.ParseInt(value, what);
      else if (option == "--calibration-error") o.calibration_error = in.ParseDouble(value, what);
      else if (option == "--seed") o.seed = static_cast<uint64_t>(in.ParseInt(value, what));
      else if (option == "--pause") {
        ClipPause pause;
        if (!ParsePause(std::string(value), &pause)) in.Fail(what + ": expected AT_S,FOR_S (AT >= 0, 0 < FOR <= 60)");
        o.pauses.push_back(pause);
      } else if (option == "--walk") {
        ClipPlacement walk;
        if (!ParsePlacement(std::string(value), &walk)) in.Fail(what + ": expected X_MM,Z_MM,HEADING_DEG,DELAY_S");
        clip.walks.push_back(walk);
      }
      else in.Fail("unknown render option " + Quote(tokens[i]));
      clip.options_text += (clip.options_text.empty() ? "" : " ") + option + " " + std::string(value);
    }
    if (o.rig.kind == RigKind::kWebcam && clip.options_text.find("--cameras") == std::string::npos) {
      o.rig.num_cameras = 1;  // the webcam rig's own
    }
    if (!clip.walks.empty() && clip.walks.size() != trials.size())
      in.Fail("expected one --walk per walker (" + std::to_string(trials.size()) + "), found " +
              std::to_string(clip.walks.size()));
    if (!clip.walks.empty() && clip.walks[0].delay_s != 0) in.Fail("the first walker's --walk delay must be 0");
    o.contact_sheet = false;
    std::string why;
    if (!o.Check(&why)) in.Fail(why);
    clips.push_back(std::move(clip));
  }
  if (clips.empty()) ThrowInputError(source, "no clips in the suite");
  return clips;
}

std::vector<SuiteClip> ReadTrackingSuite(const fs::path& path) {
  return ParseTrackingSuite(ReadTextFile(path, "a tracking suite (NAME TRIAL [render options] per line)"), path.string());
}

void RenderTrackingSuite(const std::vector<SuiteClip>& clips, const std::function<fs::path()>& data_root,
                         const fs::path& folder,
                         const std::function<void(const SuiteClip&, bool rendered)>& progress) {
  std::error_code ec;
  fs::create_directories(folder, ec);
  if (ec) ThrowInputError(folder.string(), "cannot create the folder (" + ec.message() + ")");
  for (const SuiteClip& clip : clips) {
    const fs::path out = folder / clip.name;
    if (fs::exists(out / "ground_truth.json", ec)) {
      if (progress) progress(clip, false);
      continue;
    }
    // Absolute paths: the ground truth names the source, read later from anywhere.
    const fs::path root = data_root();
    std::vector<TrialId> trials = {clip.trial};
    trials.insert(trials.end(), clip.others.begin(), clip.others.end());
    std::vector<ClipWalker> walkers;
    for (size_t w = 0; w < trials.size(); ++w) {
      ClipWalker walker;
      const fs::path asf = fs::absolute(TrialAsfPath(root, trials[w])).lexically_normal();
      const fs::path amc = fs::absolute(TrialAmcPath(root, trials[w])).lexically_normal();
      walker.skeleton = ReadAsf(asf);
      walker.motion = ReadAmc(amc, walker.skeleton);
      walker.motion.frames_per_second = 120;  // CMU's rate (AMC stores none)
      walker.source = {asf.string(), amc.string()};
      walker.body = WalkerBody(clip.options.body, static_cast<int>(w));
      if (!clip.walks.empty()) walker.placement = clip.walks[w];
      walkers.push_back(std::move(walker));
    }
    RenderClip(walkers, {}, clip.options, out.string());
    if (progress) progress(clip, true);
  }
}

}  // namespace jgpm
