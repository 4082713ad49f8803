// Writes the model-file fuzzer's seeds: small models of every kind, trained for a few
// iterations on synthetic walks of a made-up gait skeleton (no CMU data in the seeds).
//   make_model_seeds OUT_FOLDER
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numbers>

#include "io/gait/gait_pose.h"
#include "io/mocap/asf.h"
#include "prior/model/model_file.h"
#include "prior/model/train.h"
#include "small_asf.h"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: make_model_seeds OUT_FOLDER\n");
    return 2;
  }
  using namespace jgpm;
  const std::string asf = test::GaitAsfText();
  const GaitPoseLayout layout(ParseAsf(asf, "gait.asf"), "gait.asf");
  GaitDataset dataset;
  dataset.split = "synthetic";
  dataset.options.poses_per_cycle = 6;
  dataset.channel_names = layout.channel_names();
  dataset.channel_joints = layout.channel_joints();
  for (int g = 0; g < 3; ++g) {
    GaitTrial trial;
    trial.id = {"90", "90_1" + std::to_string(g)};
    trial.cycle.clean = true;
    trial.cycle.poses.resize(6, layout.NumChannels());
    for (int p = 0; p < 6; ++p)
      for (int c = 0; c < layout.NumChannels(); ++c)
        trial.cycle.poses(p, c) = (10 + 3 * g) * std::sin(2 * std::numbers::pi * p / 6 + 0.4 * c) + c;
    dataset.trials.push_back(trial);
  }
  for (ModelKind kind : AllModelKinds()) {
    TrainingOptions options;
    options.kind = kind;
    options.full.max_iterations = 3;
    const auto model = TrainGaitModel(dataset, {"90_10", asf}, options);
    const std::filesystem::path out = std::filesystem::path(argv[1]) / (std::string(ModelKindName(kind)) + ".json");
    WriteModelFile(out, *model);
    std::printf("wrote %s\n", out.string().c_str());
  }
  return 0;
}
