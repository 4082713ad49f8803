// What a validation run leaves for people: one result as JSON (`mean_error_mm`, per-trial
// errors), a suite as one CSV row per model and case, and the paper's charts as PNGs
// (Fig. 9 interpolation, Fig. 12 reconstruction, Fig. 13 filtering: error against stride
// scale, one bar per model).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "prior/validation.h"

namespace jgpm {

struct ModelResults {
  std::string model;  // a name for tables and legends, e.g. the file's stem
  std::vector<ValidationResult> results;
};

nlohmann::json ValidationResultJson(const ValidationResult& result);

// Columns: model, task, missing, noise, scale, mean_error_mm, std_error_mm, trials, seconds.
std::string SuiteCsv(const std::vector<ModelResults>& suite);

// Writes interpolation.png, reconstruction.png and filtering.png into `folder` for the
// tasks present; returns the paths written. InputError if a file cannot be written.
std::vector<std::filesystem::path> PlotSuite(const std::vector<ModelResults>& suite,
                                             const std::filesystem::path& folder);

}  // namespace jgpm
