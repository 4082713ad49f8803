// Leave-one-subject-out evaluation (issue #15): the honest measure of how a prior fits
// people it has never seen. For each subject with a clean walking cycle, every model kind
// is trained on the other subjects' cycles and validated on that subject's (interpolation
// at s = 1, prior/eval/validation.h), without and/or with posture adaptation.
//
// Each training subject gives at most max_trials_per_subject cycles (the first in split
// order), so that one subject with many trials (CMU 35: 21) does not make the prior theirs
// alone; with 9, holding out subject 07 of the `walking` split trains on exactly the
// default `train` split. JGPM-family models with several layers learn locally (minutes),
// the others full-batch, as datasets_scripts/quickstart.sh and the README's table do.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "io/gait/gait_dataset.h"
#include "prior/eval/validation.h"
#include "prior/model/gait_model.h"
#include "prior/model/model_kind.h"
#include "prior/model/train.h"

namespace jgpm {

struct LosoFold {
  std::string subject;  // held out
  GaitDataset train;    // the other subjects' clean trials (capped per subject)
  GaitDataset test;     // the subject's clean trials
};

// The folds of a prepared dataset, one per subject with a clean cycle. InputError when
// fewer than two subjects have one, or max_trials_per_subject < 1.
std::vector<LosoFold> LosoFolds(const GaitDataset& dataset, int max_trials_per_subject);

struct LosoOptions {
  std::vector<ModelKind> kinds = {ModelKind::kPca, ModelKind::kJgpm, ModelKind::kMljgpmTorus, ModelKind::kMljgpmCyl};
  std::vector<bool> adapt = {false, true};  // posture adaptation off and/or on
  InferenceOptions inference;  // for every run; adapt_posture is set by `adapt`
  int max_trials_per_subject = 9;
  double max_training_seconds = 0;  // per model; 0: until training ends by itself
  int threads = 1;                  // validation's; training's linear algebra uses them too

  bool Check(std::string* why) const;
};

struct LosoResult {
  std::string subject;  // held out
  ModelKind kind = ModelKind::kPca;
  bool adapted = false;
  ValidationResult validation;
};

// Runs every fold. `model_for` gives the model of a kind for a fold: train it, or read it
// from an earlier run (`TrainLosoModel` trains one). `progress` (may be empty) gets each
// result with the number done and their total.
std::vector<LosoResult> RunLoso(
    const std::vector<LosoFold>& folds, const LosoOptions& options,
    const std::function<std::unique_ptr<GaitModel>(const LosoFold&, ModelKind)>& model_for,
    const std::function<void(const LosoResult&, size_t done, size_t total)>& progress = {});

// A model of `kind` trained on `fold.train` (skeleton: its first clean trial's, read from
// its data root), within max_seconds (0: no limit) on `threads`; learning as described above.
std::unique_ptr<GaitModel> TrainLosoModel(const LosoFold& fold, ModelKind kind, double max_seconds, int threads,
                                          const ProgressCallback& progress);

// One row per fold, kind and adaptation (subject, model, adapted, trials, mean_error_mm,
// std_error_mm over the trials, seconds), then one per kind and adaptation over the
// subjects (subject "mean": every trial, the mean of the subjects' errors, each subject
// weighing alike, and their standard deviation).
std::string LosoCsv(const std::vector<LosoResult>& results);

}  // namespace jgpm
