#include "prior/cli/transition_commands.h"

#include <cstdio>
#include <filesystem>
#include <memory>
#include <regex>

#include "io/base/error.h"
#include "io/base/text_reader.h"
#include "io/mocap/amc.h"
#include "io/mocap/asf.h"
#include "io/mocap/motion_file.h"
#include "prior/motion/motion_transition.h"
#include "prior/motion/synthesis.h"

namespace jgpm::cli {
namespace {

struct TransitionArguments {
  std::string from, to, asf, out, png, method = "lsopa";
  MotionTransitionOptions options;
};

// "FILE.amc[:FIRST-LAST]" (AMC frame numbers, inclusive) -> the motion, cut.
MotionInput ReadRange(const std::string& spec, const std::string& option, const std::string& asf) {
  std::string path = spec;
  std::optional<std::pair<int, int>> range;
  static const std::regex suffix(R"(^(.*):(\d+)-(\d+)$)");
  std::smatch m;
  if (std::regex_match(spec, m, suffix)) {
    path = m[1];
    try {
      range = std::pair(std::stoi(m[2]), std::stoi(m[3]));
    } catch (const std::exception&) {
      ThrowInputError(option + " " + spec, "the frame range is out of range");
    }
  }
  if (FormatFromPath(path, option) != MotionFormat::kAmc) ThrowInputError(option + " " + path, "expected an .amc file");
  MotionFileOptions files;
  if (!asf.empty()) files.asf = asf;
  const std::filesystem::path skeleton_path = SkeletonForAmc(path, files);
  MotionInput in;
  in.asf_text = ReadTextFile(skeleton_path, "an ASF skeleton");
  in.skeleton = ParseAsf(in.asf_text, skeleton_path.string());
  in.motion = ReadAmc(path, in.skeleton);
  in.source = spec;
  if (range) {
    const int first = in.motion.first_frame_number, last = first + in.motion.NumFrames() - 1;
    if (range->first > range->second || range->first < first || range->second > last) {
      ThrowInputError(option + " " + spec, "frames " + std::to_string(range->first) + "-" +
                                               std::to_string(range->second) + " are not within the file's " +
                                               std::to_string(first) + "-" + std::to_string(last));
    }
    const int rows = range->second - range->first + 1;
    in.motion.values = RowMatrixXd(in.motion.values.middleRows(range->first - first, rows));
    in.motion.first_frame_number = range->first;
  }
  return in;
}

void RunTransition(TransitionArguments a) {
  if (!ParseTransitionMethod(a.method, &a.options.method) || a.options.method == TransitionMethod::kOracle) {
    ThrowInputError("--method " + a.method, "expected lsopa, lsopa-rt, li, ri, slerp or hold");
  }
  const std::string extension = std::filesystem::path(a.out).extension().string();
  if (extension != ".amc" && extension != ".bvh") ThrowInputError("--out " + a.out, "expected a .amc or .bvh file name");
  const MotionInput from = ReadRange(a.from, "--from", a.asf);
  const MotionInput to = ReadRange(a.to, "--to", "");
  std::printf("transition: %s, %d frames at %g frames/s, from %s (%d frames) to %s (%d frames)\n",
              std::string(TransitionMethodName(a.options.method)).c_str(), a.options.transition.path.frames,
              a.options.frames_per_second, a.from.c_str(), from.motion.NumFrames(), a.to.c_str(), to.motion.NumFrames());
  std::fflush(stdout);
  const MotionTransitionResult result = TransitionBetween(from, to, a.options);
  if (result.other_skeleton) {
    std::printf("note: the motions have different skeletons; B's angles are written on A's skeleton\n");
  }
  for (const auto& file : WriteSynthesis(from.skeleton, from.asf_text, result.motion, a.out, a.png)) {
    std::printf("wrote %s\n", file.string().c_str());
  }
  std::printf("%d frames: A %d, transition %d (from frame %d), B %d; generated in %.2f s%s\n",
              result.motion.NumFrames(), result.first, result.frames, result.first,
              result.motion.NumFrames() - result.first - result.frames, result.seconds,
              result.context ? (", GPDM trained on " + std::to_string(result.context) + " + " +
                                std::to_string(result.context) + " frames")
                                   .c_str()
                             : "");
  if (a.options.method == TransitionMethod::kLsopaRetrained) {
    std::printf("retraining on [A; transition; B] moved the transition's latent points by %.3f |b - a| on average "
                "and changed a gait channel of it by %.3f degrees at most\n",
                result.retrain_latent_shift, result.retrain_change_deg);
  }
}

}  // namespace

void AddTransitionCommands(CLI::App& app) {
  auto a = std::make_shared<TransitionArguments>();
  CLI::App* t = app.add_subcommand("transition", "Generate the motion between two motions (LSOPA, or lsopa-rt, li, ri, slerp, hold)");
  t->add_option("--from", a->from, "motion A: FILE.amc[:FIRST-LAST] (AMC frame numbers)")->required();
  t->add_option("--to", a->to, "motion B: FILE.amc[:FIRST-LAST]")->required();
  t->add_option("--asf", a->asf, "A's skeleton (default: the ASF beside the AMC)");
  t->add_option("--frames", a->options.transition.path.frames, "transition frames N")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
  t->add_option("--method", a->method, "lsopa, lsopa-rt (LSOPA, then Algorithm 1's retraining on [A; transition; B]), li (straight latent "
                "line), ri (random latent points), slerp, hold (A's last frame)")
      ->capture_default_str();
  t->add_option("--seed", a->options.transition.seed, "ri: the random points' seed")->capture_default_str();
  t->add_option("--out", a->out, "OUT.amc (with OUT.asf beside it) or OUT.bvh: A, the transition and B")->required();
  t->add_option("--png", a->png, "also a strip of stick figures");
  t->callback([a] { RunTransition(*a); });
}

}  // namespace jgpm::cli
