// A prepared gait dataset: one resampled gait cycle per walking trial of a split, written
// as JSON (`jgpm data cycles`) and read back by training and evaluation.
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "io/gait/gait_cycle.h"
#include "io/gait/split.h"

namespace jgpm {

struct GaitTrial {
  TrialId id;
  std::string asf;  // paths relative to the data root
  std::string amc;
  int frames = 0;
  double frames_per_second = 0;
  GaitCycle cycle;  // cycle.clean says whether the trial is usable
};

struct GaitDataset {
  static constexpr int kFormatVersion = 1;
  std::string split;      // as given (name or path)
  std::string data_root;
  GaitCycleOptions options;
  std::vector<std::string> joint_names;    // GaitJoints()
  std::vector<std::string> channel_names;  // GaitPoseLayout channels
  std::vector<int> channel_joints;
  std::vector<GaitTrial> trials;

  int NumClean() const;
};

// Called after each trial with its index (from 0), the number of trials and the trial.
using GaitProgress = std::function<void(int, int, const GaitTrial&)>;

// Reads each trial's ASF and AMC from `data_root` and extracts its cycle. InputError if a
// file is missing or malformed, or a skeleton lacks a gait joint; a trial without a clean
// cycle is kept with cycle.clean = false and the reason.
GaitDataset PrepareGaitDataset(const std::filesystem::path& data_root, const std::string& split,
                               const std::vector<TrialId>& trials, const GaitCycleOptions& options,
                               const GaitProgress& progress = nullptr);

std::string FormatGaitDatasetJson(const GaitDataset& dataset);
void WriteGaitDataset(const std::filesystem::path& path, const GaitDataset& dataset);
// Parses the JSON text of a gait dataset; `source` names it in errors. InputError naming
// the source and the field for malformed JSON, another format version, wrong array sizes,
// non-finite numbers, integers out of range or frame numbers outside the trial.
GaitDataset ParseGaitDataset(const std::string& text, const std::string& source);
// ParseGaitDataset of a file's text.
GaitDataset ReadGaitDataset(const std::filesystem::path& path);

// The per-trial table `jgpm data cycles` prints, with a summary line.
std::string FormatGaitDatasetTable(const GaitDataset& dataset);

}  // namespace jgpm
