#include "io/cli/data_commands.h"

#include <cstdio>
#include <iostream>
#include <map>
#include <memory>

#include "io/base/error.h"
#include "io/cli/progress.h"
#include "io/gait/data_root.h"
#include "io/gait/gait_dataset.h"
#include "io/gait/split.h"
#include "io/mocap/motion_file.h"

namespace jgpm::cli {
namespace {

struct DataOptions {
  std::string file;
  std::string out;
  std::string asf;
  double fps = 120.0;
  std::string bvh_unit = "cm";
  std::string split = "train";
  std::string data;
  int poses = 30;
};

const std::map<std::string, double> kBvhUnits = {{"mm", 1.0}, {"cm", 10.0}, {"m", 1000.0},
                                                 {"in", 25.4}};

MotionFileOptions ToMotionFileOptions(const DataOptions& o) {
  MotionFileOptions options;
  if (!o.asf.empty()) options.asf = o.asf;
  options.amc_frames_per_second = o.fps;
  options.bvh_mm_per_unit = kBvhUnits.at(o.bvh_unit);
  return options;
}

void AddMotionFileOptions(CLI::App* command, DataOptions* o) {
  command->add_option("--asf", o->asf, "ASF skeleton of an AMC motion (default: NN.asf next to NN_TT.amc)")
      ->check(CLI::ExistingFile);
  command->add_option("--fps", o->fps, "frame rate of AMC motion (AMC stores none; CMU: 120)")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  command->add_option("--bvh-unit", o->bvh_unit, "unit of BVH lengths (BVH stores none)")
      ->check(CLI::IsMember({"mm", "cm", "m", "in"}))
      ->capture_default_str();
}

void RunCycles(const DataOptions& o) {
  GaitCycleOptions options;
  options.poses_per_cycle = o.poses;
  const std::filesystem::path root = ResolveDataRoot(o.data.empty() ? std::nullopt
                                                                    : std::optional(o.data));
  const std::filesystem::path split_path = ResolveSplitPath(o.split, JGPM_SPLITS_DIR);
  const std::vector<TrialId> ids = ReadSplit(split_path);
  std::printf("data root %s, split %s (%zu trials)\n", root.string().c_str(),
              split_path.string().c_str(), ids.size());
  std::fflush(stdout);
  ProgressLine line("cycles", 0.2);
  const GaitDataset dataset = PrepareGaitDataset(root, o.split, ids, options, [&](int i, int n, const GaitTrial& trial) {
    line.Update(i + 1, n, "trials", trial.id.name);
  });
  line.Finish();
  WriteGaitDataset(o.out, dataset);
  std::fputs(FormatGaitDatasetTable(dataset).c_str(), stdout);
  std::printf("wrote %s\n", o.out.c_str());
}

}  // namespace

void AddDataCommands(CLI::App& app) {
  CLI::App* data = app.add_subcommand("data", "Motion-capture files and gait datasets");
  data->require_subcommand(1);
  auto o = std::make_shared<DataOptions>();

  CLI::App* info = data->add_subcommand("info", "Frames, rate, joints and channels of an ASF, AMC or BVH file");
  info->add_option("FILE", o->file, "ASF, AMC or BVH file")->required();
  AddMotionFileOptions(info, o.get());
  info->callback([o] { std::fputs(DescribeMotionFile(o->file, ToMotionFileOptions(*o)).c_str(), stdout); });

  CLI::App* convert = data->add_subcommand("convert", "Convert AMC <-> BVH (joint positions are kept)");
  convert->add_option("IN", o->file, "AMC or BVH motion")->required();
  convert->add_option("--out", o->out, "output .amc or .bvh (written only on success)")->required();
  AddMotionFileOptions(convert, o.get());
  convert->callback([o] {
    std::puts(ConvertMotionFile(o->file, o->out, ToMotionFileOptions(*o)).c_str());
  });

  CLI::App* cycles = data->add_subcommand(
      "cycles", "Extract one gait cycle per walking trial of a split and write the dataset JSON");
  cycles->add_option("--split", o->split, "split name (datasets_scripts/splits/NAME.txt) or file")
      ->capture_default_str();
  cycles->add_option("--out", o->out, "output JSON")->required();
  cycles->add_option("--data", o->data, "data root (default: $JGPM_DATA, ./data/cmu, ../shared/data/cmu)");
  cycles->add_option("--poses", o->poses, "poses per resampled cycle")
      ->check(CLI::Range(2, 10000))
      ->capture_default_str();
  cycles->callback([o] { RunCycles(*o); });
}

}  // namespace jgpm::cli
