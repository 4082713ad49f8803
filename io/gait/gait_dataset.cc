#include "io/gait/gait_dataset.h"

#include <cmath>
#include <cstdio>
#include <map>

#include "io/base/error.h"
#include "io/base/json_file.h"
#include "io/base/text_reader.h"
#include "io/mocap/amc.h"
#include "io/mocap/asf.h"

namespace jgpm {
namespace fs = std::filesystem;
using nlohmann::json;

int GaitDataset::NumClean() const {
  int n = 0;
  for (const GaitTrial& trial : trials) n += trial.cycle.clean ? 1 : 0;
  return n;
}

GaitDataset PrepareGaitDataset(const fs::path& data_root, const std::string& split,
                               const std::vector<TrialId>& trials, const GaitCycleOptions& options,
                               const GaitProgress& progress) {
  GaitDataset dataset;
  dataset.split = split;
  dataset.data_root = fs::absolute(data_root).lexically_normal().string();
  dataset.options = options;
  for (const GaitJoint& joint : GaitJoints()) dataset.joint_names.emplace_back(joint.name);
  std::map<std::string, Skeleton> skeletons;  // by subject
  for (size_t i = 0; i < trials.size(); ++i) {
    const TrialId& id = trials[i];
    const fs::path asf = TrialAsfPath(data_root, id);
    auto it = skeletons.find(id.subject);
    if (it == skeletons.end()) it = skeletons.emplace(id.subject, ReadAsf(asf)).first;
    const Skeleton& skeleton = it->second;
    const GaitPoseLayout layout(skeleton, asf.string());
    if (dataset.channel_names.empty()) {
      dataset.channel_names = layout.channel_names();
      dataset.channel_joints = layout.channel_joints();
    } else if (dataset.channel_names != layout.channel_names()) {
      ThrowInputError(asf.string(), "its bones have other dofs than the split's first skeleton, "
                                    "so its gait channels differ");
    }
    GaitTrial trial;
    trial.id = id;
    trial.asf = fs::relative(asf, data_root).string();
    trial.amc = fs::relative(TrialAmcPath(data_root, id), data_root).string();
    const Motion motion = ReadAmc(TrialAmcPath(data_root, id), skeleton);
    trial.frames = motion.NumFrames();
    trial.frames_per_second = motion.frames_per_second;
    trial.cycle = ExtractGaitCycle(layout, motion, options);
    dataset.trials.push_back(std::move(trial));
    if (progress) progress(static_cast<int>(i), static_cast<int>(trials.size()), dataset.trials.back());
  }
  return dataset;
}

std::string FormatGaitDatasetJson(const GaitDataset& dataset) {
  json root;
  root["format"] = "jgpm-gait-dataset";
  root["version"] = GaitDataset::kFormatVersion;
  root["split"] = dataset.split;
  root["data_root"] = dataset.data_root;
  const GaitCycleOptions& o = dataset.options;
  root["options"] = {{"poses_per_cycle", o.poses_per_cycle},
                     {"min_cycle_s", o.min_cycle_s},
                     {"max_cycle_s", o.max_cycle_s},
                     {"min_periodicity", o.min_periodicity},
                     {"min_thigh_swing_deg", o.min_thigh_swing_deg},
                     {"max_closure_deg", o.max_closure_deg}};
  root["joints"] = dataset.joint_names;
  root["channels"] = dataset.channel_names;
  root["channel_joints"] = dataset.channel_joints;
  root["angle_unit"] = "deg";
  json trials = json::array();
  for (const GaitTrial& trial : dataset.trials) {
    const GaitCycle& c = trial.cycle;
    json poses = json::array();
    for (int k = 0; k < c.poses.rows(); ++k) {
      poses.push_back(std::vector<double>(c.poses.row(k).begin(), c.poses.row(k).end()));
    }
    trials.push_back({{"id", trial.id.name},
                      {"subject", trial.id.subject},
                      {"asf", trial.asf},
                      {"amc", trial.amc},
                      {"frames", trial.frames},
                      {"frames_per_second", trial.frames_per_second},
                      {"clean", c.clean},
                      {"problem", c.problem},
                      {"cycle",
                       {{"start_frame", c.start_frame},
                        {"end_frame", c.end_frame},
                        {"length_frames", c.LengthFrames()},
                        {"period_frames", c.period_frames},
                        {"periodicity", c.periodicity},
                        {"thigh_swing_deg", c.thigh_swing_deg},
                        {"closure_deg", c.closure_deg},
                        {"heading_deg", c.heading_deg}}},
                      {"poses", poses}});
  }
  root["trials"] = trials;
  return FormatJson(root);
}

void WriteGaitDataset(const fs::path& path, const GaitDataset& dataset) {
  WriteFileAtomic(path, FormatGaitDatasetJson(dataset));
}


GaitDataset ParseGaitDataset(const std::string& text, const std::string& source) {
  const json root = ParseJson(text, source);
  const JsonReader in(source);
  if (!root.is_object() || in.Get<std::string>(root, "format", "") != "jgpm-gait-dataset") {
    ThrowInputError(source, "not a jgpm gait dataset (expected \"format\": \"jgpm-gait-dataset\")");
  }
  const int version = in.Get<int>(root, "version", "");
  if (version != GaitDataset::kFormatVersion) {
    ThrowInputError(source, "gait dataset version " + std::to_string(version) +
                                       " is not supported (expected " +
                                       std::to_string(GaitDataset::kFormatVersion) + ")");
  }
  GaitDataset dataset;
  dataset.split = in.Get<std::string>(root, "split", "");
  dataset.data_root = in.Get<std::string>(root, "data_root", "");
  const json& options = in.Field(root, "options", "");
  GaitCycleOptions& o = dataset.options;
  o.poses_per_cycle = in.Get<int>(options, "poses_per_cycle", "options.");
  o.min_cycle_s = in.Get<double>(options, "min_cycle_s", "options.");
  o.max_cycle_s = in.Get<double>(options, "max_cycle_s", "options.");
  o.min_periodicity = in.Get<double>(options, "min_periodicity", "options.");
  o.min_thigh_swing_deg = in.Get<double>(options, "min_thigh_swing_deg", "options.");
  o.max_closure_deg = in.Get<double>(options, "max_closure_deg", "options.");
  std::string why;
  if (!o.Check(&why)) in.Fail("options", why);
  dataset.joint_names = in.Get<std::vector<std::string>>(root, "joints", "");
  dataset.channel_names = in.Get<std::vector<std::string>>(root, "channels", "");
  dataset.channel_joints = in.Get<std::vector<int>>(root, "channel_joints", "");
  const int channels = static_cast<int>(dataset.channel_names.size());
  if (channels == 0) in.Fail("channels", "is empty");
  if (static_cast<int>(dataset.channel_joints.size()) != channels) {
    in.Fail("channel_joints", "must have one entry per channel");
  }
  for (int j : dataset.channel_joints) {
    if (j < 0 || j >= static_cast<int>(dataset.joint_names.size())) {
      in.Fail("channel_joints", "holds an index outside joints");
    }
  }
  const json& trials = in.Field(root, "trials", "");
  if (!trials.is_array()) in.Fail("trials", "expected an array");
  for (size_t i = 0; i < trials.size(); ++i) {
    const std::string where = "trials[" + std::to_string(i) + "].";
    const json& t = trials[i];
    GaitTrial trial;
    if (!ParseTrialId(in.Get<std::string>(t, "id", where), &trial.id)) {
      in.Fail(where + "id", "expected a trial id such as 35_01");
    }
    trial.asf = in.Get<std::string>(t, "asf", where);
    trial.amc = in.Get<std::string>(t, "amc", where);
    trial.frames = in.Get<int>(t, "frames", where);
    if (trial.frames < 0) in.Fail(where + "frames", "must not be negative");
    trial.frames_per_second = in.Get<double>(t, "frames_per_second", where);
    if (!(trial.frames_per_second > 0)) in.Fail(where + "frames_per_second", "must be positive");
    GaitCycle& c = trial.cycle;
    c.clean = in.Get<bool>(t, "clean", where);
    c.problem = in.Get<std::string>(t, "problem", where);
    const json& cycle = in.Field(t, "cycle", where);
    const std::string cw = where + "cycle.";
    c.start_frame = in.Get<int>(cycle, "start_frame", cw);
    c.end_frame = in.Get<int>(cycle, "end_frame", cw);
    // Frame numbers count from the AMC's first (1 for CMU), so only the length is bounded.
    if (c.start_frame < 0 || c.end_frame < c.start_frame ||
        c.end_frame - c.start_frame > trial.frames) {
      in.Fail(cw + "end_frame", "expected 0 <= start_frame <= end_frame <= start_frame + frames (" +
                                    std::to_string(trial.frames) + "), found " +
                                    std::to_string(c.start_frame) + " and " +
                                    std::to_string(c.end_frame));
    }
    c.period_frames = in.Get<double>(cycle, "period_frames", cw);
    c.periodicity = in.Get<double>(cycle, "periodicity", cw);
    c.thigh_swing_deg = in.Get<double>(cycle, "thigh_swing_deg", cw);
    c.closure_deg = in.Get<double>(cycle, "closure_deg", cw);
    c.heading_deg = in.Get<double>(cycle, "heading_deg", cw);
    const auto poses = in.Get<std::vector<std::vector<double>>>(t, "poses", where);
    if (c.clean && static_cast<int>(poses.size()) != o.poses_per_cycle) {
      in.Fail(where + "poses", "expected " + std::to_string(o.poses_per_cycle) + " poses, found " +
                                   std::to_string(poses.size()));
    }
    // Every row is checked before the matrix is sized: rows x channels of a file of empty
    // rows and empty channel names would otherwise grow with the square of its size.
    for (size_t k = 0; k < poses.size(); ++k) {
      if (static_cast<int>(poses[k].size()) != channels) {
        in.Fail(where + "poses[" + std::to_string(k) + "]",
                "expected " + std::to_string(channels) + " values, found " +
                    std::to_string(poses[k].size()));
      }
    }
    c.poses.resize(static_cast<int>(poses.size()), channels);
    for (size_t k = 0; k < poses.size(); ++k) {
      for (int ch = 0; ch < channels; ++ch) {
        if (!std::isfinite(poses[k][ch])) {
          in.Fail(where + "poses[" + std::to_string(k) + "]", "holds a non-finite value");
        }
        c.poses(static_cast<int>(k), ch) = poses[k][ch];
      }
    }
    dataset.trials.push_back(std::move(trial));
  }
  return dataset;
}

GaitDataset ReadGaitDataset(const fs::path& path) {
  return ParseGaitDataset(ReadTextFile(path, "a gait dataset (JSON from `jgpm data cycles`)"),
                          path.string());
}

std::string FormatGaitDatasetTable(const GaitDataset& dataset) {
  std::string out;
  char line[256];
  std::snprintf(line, sizeof(line), "%-8s %6s %6s %6s %7s %7s %6s %8s %8s  %s\n", "trial",
                "frames", "start", "end", "length", "seconds", "r", "closure", "heading", "status");
  out += line;
  double sum = 0, min = 1e9, max = 0;
  for (const GaitTrial& trial : dataset.trials) {
    const GaitCycle& c = trial.cycle;
    if (c.LengthFrames() > 0) {
      std::snprintf(line, sizeof(line), "%-8s %6d %6d %6d %7d %7.3f %6.3f %8.2f %8.1f  %s\n",
                    trial.id.name.c_str(), trial.frames, c.start_frame, c.end_frame,
                    c.LengthFrames(), c.LengthFrames() / trial.frames_per_second, c.periodicity,
                    c.closure_deg, c.heading_deg, c.clean ? "ok" : ("FLAGGED: " + c.problem).c_str());
    } else {
      std::snprintf(line, sizeof(line), "%-8s %6d %6s %6s %7s %7s %6s %8s %8s  FLAGGED: %s\n",
                    trial.id.name.c_str(), trial.frames, "-", "-", "-", "-", "-", "-", "-",
                    c.problem.c_str());
    }
    out += line;
    if (c.clean) {
      sum += c.LengthFrames();
      min = std::min<double>(min, c.LengthFrames());
      max = std::max<double>(max, c.LengthFrames());
    }
  }
  const int clean = dataset.NumClean();
  std::snprintf(line, sizeof(line),
                "%d trials, %d clean cycles, %d flagged; clean cycle length %s frames; %d poses "
                "x %zu channels per cycle\n",
                static_cast<int>(dataset.trials.size()), clean,
                static_cast<int>(dataset.trials.size()) - clean,
                clean ? (std::to_string(static_cast<int>(min)) + "-" +
                         std::to_string(static_cast<int>(max)) + ", mean " +
                         std::to_string(static_cast<int>(std::lround(sum / clean))))
                            .c_str()
                      : "n/a",
                dataset.options.poses_per_cycle, dataset.channel_names.size());
  out += line;
  return out;
}

}  // namespace jgpm
