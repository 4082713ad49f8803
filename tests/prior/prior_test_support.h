// Small synthetic gait datasets for the prior tests: smooth periodic "walks" whose style
// varies with the gait, no CMU data needed.
#pragma once

#include <cmath>
#include <string>

#include "io/gait_dataset.h"

namespace jgpm::test {

inline GaitDataset SyntheticGaitDataset(int gaits, int poses, int channels) {
  GaitDataset dataset;
  dataset.split = "synthetic";
  dataset.options.poses_per_cycle = poses;
  for (int c = 0; c < channels; ++c) {
    dataset.channel_names.push_back("bone" + std::to_string(c) + ".rx");
    dataset.channel_joints.push_back(c);
  }
  for (int g = 0; g < gaits; ++g) {
    GaitTrial trial;
    trial.id.subject = "90";
    trial.id.name = "90_" + std::to_string(10 + g);
    trial.cycle.clean = true;
    trial.cycle.poses.resize(poses, channels);
    for (int p = 0; p < poses; ++p) {
      const double phase = 6.283185307179586 * p / poses;
      for (int c = 0; c < channels; ++c) {
        trial.cycle.poses(p, c) = (10 + 3 * g) * std::sin(phase + 0.4 * c) + 5 * std::cos(2 * phase + g) + c;
      }
    }
    dataset.trials.push_back(trial);
  }
  return dataset;
}

}  // namespace jgpm::test
