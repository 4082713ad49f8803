// A model file's pose table (tracker/state/pose_table.h), kept beside it as MODEL.table, so
// that a run does not spend seconds rebuilding what the last run built: on 2 cores the
// ML-JGPM table takes about 3 s, longer than tracking a 4-second clip. The file holds a
// key: the table's version (PoseTable::kVersion), a hash of the model file's bytes, of the
// skeleton the poses are placed on (--asf) and of the table's options. A file with another key (the model retrained, other
// options) or damaged is rebuilt and replaced (atomically); when the model's folder cannot
// be written the table is built and nothing is kept.
#pragma once

#include <functional>
#include <memory>
#include <string>

#include "prior/model/gait_model.h"
#include "tracker/state/pose_table.h"

namespace jgpm {

// Where the table of `model_path` is kept.
std::string PoseTableCachePath(const std::string& model_path);

// The table of `model` (read from `model_path`, placed on the skeleton `asf_path` when not
// empty) with `options`: from the cache when its key matches, else built and kept.
// `note` (may be empty) hears why a kept table was not used or could not be kept.
std::shared_ptr<const PoseTable> CachedPoseTable(const GaitModel& model, const std::string& model_path,
                                                 const std::string& asf_path, const PoseTableOptions& options,
                                                 const std::function<void(const std::string&)>& note = {});

// The same in two steps, so that the kept table is read while the model file is parsed
// (each took about half a second for ML-JGPM on one core): the kept table whose key
// matches, read without the model (null when there is none, or it is stale or damaged:
// then said to `note`); then `kept` when it fits `model` (its kind, bones and channels),
// else the table built and kept.
std::unique_ptr<PoseTable> ReadKeptPoseTable(const std::string& model_path, const std::string& asf_path,
                                             const PoseTableOptions& options,
                                             const std::function<void(const std::string&)>& note = {});
std::shared_ptr<const PoseTable> CachedPoseTable(const GaitModel& model, const std::string& model_path,
                                                 const std::string& asf_path, const PoseTableOptions& options,
                                                 const std::function<void(const std::string&)>& note,
                                                 std::unique_ptr<PoseTable> kept);

}  // namespace jgpm
