// libFuzzer target: ParseGaitDataset must either return a dataset whose arrays agree with
// each other or throw InputError; what parses must format (JSON and the per-trial table)
// and parse back to exactly the same dataset.
#include <bit>
#include <cstddef>
#include <cstdint>
#include <string>

#include "io/base/error.h"
#include "io/gait/gait_dataset.h"

namespace {

bool Same(double a, double b) { return std::bit_cast<uint64_t>(a) == std::bit_cast<uint64_t>(b); }

bool SameCycle(const jgpm::GaitCycle& a, const jgpm::GaitCycle& b) {
  if (a.poses.rows() != b.poses.rows() || a.poses.cols() != b.poses.cols()) return false;
  for (Eigen::Index i = 0; i < a.poses.size(); ++i) {
    if (!Same(a.poses.data()[i], b.poses.data()[i])) return false;
  }
  return a.clean == b.clean && a.problem == b.problem && a.start_frame == b.start_frame &&
         a.end_frame == b.end_frame && Same(a.period_frames, b.period_frames) &&
         Same(a.periodicity, b.periodicity) && Same(a.thigh_swing_deg, b.thigh_swing_deg) &&
         Same(a.closure_deg, b.closure_deg) && Same(a.heading_deg, b.heading_deg);
}

bool SameDataset(const jgpm::GaitDataset& a, const jgpm::GaitDataset& b) {
  const jgpm::GaitCycleOptions& o = a.options;
  const jgpm::GaitCycleOptions& p = b.options;
  if (a.split != b.split || a.data_root != b.data_root || o.poses_per_cycle != p.poses_per_cycle ||
      !Same(o.min_cycle_s, p.min_cycle_s) || !Same(o.max_cycle_s, p.max_cycle_s) ||
      !Same(o.min_periodicity, p.min_periodicity) ||
      !Same(o.min_thigh_swing_deg, p.min_thigh_swing_deg) ||
      !Same(o.max_closure_deg, p.max_closure_deg) || a.joint_names != b.joint_names ||
      a.channel_names != b.channel_names || a.channel_joints != b.channel_joints ||
      a.trials.size() != b.trials.size()) {
    return false;
  }
  for (size_t i = 0; i < a.trials.size(); ++i) {
    const jgpm::GaitTrial& s = a.trials[i];
    const jgpm::GaitTrial& t = b.trials[i];
    if (s.id.name != t.id.name || s.id.subject != t.id.subject || s.asf != t.asf ||
        s.amc != t.amc || s.frames != t.frames || !Same(s.frames_per_second, t.frames_per_second) ||
        !SameCycle(s.cycle, t.cycle)) {
      return false;
    }
  }
  return true;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const jgpm::GaitDataset dataset = jgpm::ParseGaitDataset(text, "fuzz.json");
    const int channels = static_cast<int>(dataset.channel_names.size());
    JGPM_CHECK(channels > 0 && dataset.channel_joints.size() == dataset.channel_names.size());
    for (int j : dataset.channel_joints) {
      JGPM_CHECK(j >= 0 && j < static_cast<int>(dataset.joint_names.size()));
    }
    for (const jgpm::GaitTrial& trial : dataset.trials) {
      JGPM_CHECK(trial.cycle.poses.cols() == channels || trial.cycle.poses.rows() == 0);
      JGPM_CHECK(!trial.cycle.clean || trial.cycle.poses.rows() == dataset.options.poses_per_cycle);
      JGPM_CHECK(trial.cycle.poses.allFinite());
    }
    jgpm::FormatGaitDatasetTable(dataset);
    const jgpm::GaitDataset back =
        jgpm::ParseGaitDataset(jgpm::FormatGaitDatasetJson(dataset), "back.json");
    JGPM_CHECK(SameDataset(dataset, back));
  } catch (const jgpm::InputError&) {
  }
  return 0;
}
