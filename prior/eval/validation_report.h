// What a validation run leaves for people: one result as JSON (`mean_error_mm`, per-trial,
// per-joint and per-channel errors), a suite as one CSV row per model and case (and a
// detail CSV: a row per joint and channel), and the paper's charts as PNGs
// (Fig. 9 interpolation, Fig. 12 reconstruction, Fig. 13 filtering: error against stride
// scale, one bar per model).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "io/base/output_batch.h"
#include "prior/eval/validation.h"

namespace jgpm {

nlohmann::json ValidationResultJson(const ValidationResult& result);

// Columns: model, task, missing, noise, scale, mean_error_mm, std_error_mm, trials, seconds.
std::string SuiteCsv(const std::vector<ModelResults>& suite);

// Where each case's error comes from, a row per model, case and joint (kind joint_mm, mm)
// or channel (kind channel_deg, degrees; and posture_offset_deg, the mean offset posture
// adaptation found): model, task, missing, noise, scale, kind, name, error.
std::string SuiteDetailCsv(const std::vector<ModelResults>& suite);

// Adds interpolation.png, reconstruction.png and filtering.png in `folder` to `batch`, for
// the tasks present, and joints.png: each joint's error per model, averaged over the cases.
void PlotSuite(const std::vector<ModelResults>& suite, const std::filesystem::path& folder, OutputBatch* batch);

// What `jgpm eval` writes, all files or none (InputError if one cannot be written; nothing
// is then left): with `json`, the results as JSON (one model and case: its fields at the
// top level and "model"; else "models": [{model, results}]), with "split"; with `folder`,
// `csv_name` (SuiteCsv), its stem + "_detail.csv" (SuiteDetailCsv) and the charts. `model_paths` name the models as the user gave
// them. Returns the files written.
std::vector<std::filesystem::path> WriteValidationOutputs(const std::vector<ModelResults>& suite,
                                                          const std::vector<std::string>& model_paths,
                                                          const std::string& split,
                                                          const std::filesystem::path& json,
                                                          const std::filesystem::path& folder,
                                                          const std::string& csv_name);

}  // namespace jgpm
