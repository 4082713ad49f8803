#include "prior/eval/loso.h"

#include <cmath>
#include <cstdio>
#include <algorithm>
#include <map>

#include "io/base/error.h"

namespace jgpm {

bool LosoOptions::Check(std::string* why) const {
  const char* problem = nullptr;
  if (kinds.empty()) problem = "give at least one model kind";
  else if (adapt.empty()) problem = "give at least one adaptation setting";
  else if (max_trials_per_subject < 1) problem = "max_trials_per_subject must be >= 1";
  else if (!(max_training_seconds >= 0)) problem = "max_training_seconds must be >= 0";
  else if (threads < 1) problem = "threads must be >= 1";
  std::string why_inference;
  if (!problem && !inference.Check(&why_inference)) problem = why_inference.c_str();
  if (problem && why) *why = problem;  // `why` may be null
  return problem == nullptr;
}

std::vector<LosoFold> LosoFolds(const GaitDataset& dataset, int max_trials_per_subject) {
  if (max_trials_per_subject < 1) ThrowInputError("leave-one-subject-out", "at most 0 trials per subject");
  std::vector<std::string> subjects;  // in dataset order
  for (const GaitTrial& trial : dataset.trials) {
    if (trial.cycle.clean && std::find(subjects.begin(), subjects.end(), trial.id.subject) == subjects.end()) {
      subjects.push_back(trial.id.subject);
    }
  }
  if (subjects.size() < 2) {
    ThrowInputError("dataset " + dataset.split, "leave-one-subject-out needs clean cycles of at least two subjects, it has " +
                                                    std::to_string(subjects.size()));
  }
  std::vector<LosoFold> folds;
  for (const std::string& held_out : subjects) {
    LosoFold fold{held_out, dataset, dataset};
    fold.train.trials.clear();
    fold.test.trials.clear();
    std::map<std::string, int> taken;
    for (const GaitTrial& trial : dataset.trials) {
      if (!trial.cycle.clean) continue;
      if (trial.id.subject == held_out) fold.test.trials.push_back(trial);
      else if (taken[trial.id.subject]++ < max_trials_per_subject) fold.train.trials.push_back(trial);
    }
    fold.train.split = dataset.split + " without " + held_out;
    fold.test.split = dataset.split + " of " + held_out;
    folds.push_back(std::move(fold));
  }
  return folds;
}

std::unique_ptr<GaitModel> TrainLosoModel(const LosoFold& fold, ModelKind kind, double max_seconds, int threads,
                                          const ProgressCallback& progress) {
  TrainingOptions options;
  options.kind = kind;
  options.learning = SpecFor(kind, 1).layer_scales.size() > 1 ? Learning::kLocal : Learning::kFull;
  options.threads = threads;
  options.budget.max_seconds = max_seconds;
  options.progress = progress;
  return TrainGaitModel(fold.train, ChooseReferenceSkeleton(fold.train, fold.train.data_root), options);
}

std::vector<LosoResult> RunLoso(
    const std::vector<LosoFold>& folds, const LosoOptions& options,
    const std::function<std::unique_ptr<GaitModel>(const LosoFold&, ModelKind)>& model_for,
    const std::function<void(const LosoResult&, size_t done, size_t total)>& progress) {
  std::string why;
  if (!options.Check(&why)) ThrowInputError("leave-one-subject-out options", why);
  std::vector<LosoResult> results;
  const size_t total = folds.size() * options.kinds.size() * options.adapt.size();
  for (const LosoFold& fold : folds) {
    for (ModelKind kind : options.kinds) {
      const std::unique_ptr<GaitModel> model = model_for(fold, kind);
      const std::vector<ValidationTrial> trials = LoadValidationTrials(fold.test, *model);
      for (const bool adapt : options.adapt) {
        InferenceOptions inference = options.inference;
        inference.adapt_posture = adapt;
        results.push_back({fold.subject, kind, adapt, Validate(*model, trials, ValidationCase{}, inference, options.threads)});
        if (progress) progress(results.back(), results.size(), total);
      }
    }
  }
  return results;
}

std::string LosoCsv(const std::vector<LosoResult>& results) {
  auto number = [](double value) {
    char text[32];
    std::snprintf(text, sizeof(text), "%.3f", value);
    return std::string(text);
  };
  std::string csv = "subject,model,adapted,trials,mean_error_mm,std_error_mm,seconds\n";
  // Per kind and adaptation, in the order first seen: the subjects' errors and trials.
  struct Group {
    std::string key;
    std::vector<double> errors;
    size_t trials = 0;
  };
  std::vector<Group> groups;
  for (const LosoResult& r : results) {
    const std::string key = std::string(ModelKindName(r.kind)) + "," + (r.adapted ? "yes" : "no");
    csv += r.subject + "," + key + "," + std::to_string(r.validation.trials.size()) + "," +
           number(r.validation.mean_error_mm) + "," + number(r.validation.std_error_mm) + "," +
           number(r.validation.seconds) + "\n";
    auto it = std::find_if(groups.begin(), groups.end(), [&key](const Group& g) { return g.key == key; });
    if (it == groups.end()) it = groups.insert(groups.end(), Group{key, {}, 0});
    it->errors.push_back(r.validation.mean_error_mm);
    it->trials += r.validation.trials.size();
  }
  for (const Group& g : groups) {
    double mean = 0, square = 0;
    for (double e : g.errors) mean += e / g.errors.size();
    for (double e : g.errors) square += (e - mean) * (e - mean);
    const double std = g.errors.size() > 1 ? std::sqrt(square / (g.errors.size() - 1)) : 0.0;
    csv += "mean," + g.key + "," + std::to_string(g.trials) + "," + number(mean) + "," + number(std) + ",\n";
  }
  return csv;
}

}  // namespace jgpm
