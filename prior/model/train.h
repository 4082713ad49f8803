// Training a gait model of any kind from a prepared gait dataset.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include "io/gait/gait_dataset.h"
#include "prior/learning/full_trainer.h"
#include "prior/learning/local_trainer.h"
#include "prior/model/gait_model.h"

namespace jgpm {

struct TrainingOptions {
  ModelKind kind = ModelKind::kMljgpmTorus;
  Learning learning = Learning::kFull;  // a GP model's: full, local or sparse (PCA's is closed form)
  uint64_t seed = 1;                 // local learning's choice of reference points
  int threads = 0;                   // linear-algebra threads; 0: OpenBLAS's default
  double topology_sigma2 = 0.01;     // sigma^2 of the LLE topology energy
  FullTrainingOptions full;           // full and sparse learning
  int inducing = 100;                 // sparse learning: inducing inputs per GP (3..N)
  LocalTrainingOptions local;
  ProgressCallback progress;         // overrides full.progress and local.progress
  TrainingBudget budget;             // when set, overrides full.budget and local.budget
  // Where a GP model starts instead of the initial values below (a model trained further,
  // e.g. Algorithm 1's retraining of a transition's GPDM); its sizes must be the model's.
  std::optional<GpParameters> start;

  bool Check(std::string* why) const;
};

// The reference skeleton the model's joint positions use.
struct ReferenceSkeleton {
  std::string trial;  // e.g. "35_01"
  std::string asf;    // ASF text
};

// The training set's motion sequences: one per layer and gait (its gait cycle).
std::vector<Sequence> TrainingSequences(const TrainingSet& set);

// The first clean trial's skeleton, its ASF read from `data_root` (a dataset's own
// data_root, or the one given). InputError when no trial is clean or the ASF is missing.
ReferenceSkeleton ChooseReferenceSkeleton(const GaitDataset& dataset, const std::filesystem::path& data_root);

// Initial latent points: the topology prior's coordinates (JGPM family), else the
// training poses' 3 leading principal components scaled to unit variance. Hyper-parameters
// start at b = (1, 1, 100) (noise std 0.1 of a normalised channel), a = (1, 1, 0.1, 1e4),
// W = 1. InputError for bad options or data. Training that ends in a numerical failure
// returns the best model found before it, its summary saying so. The OpenBLAS thread
// count (`threads`) applies while training and is restored after.
std::unique_ptr<GaitModel> TrainGaitModel(const GaitDataset& dataset,
                                          const ReferenceSkeleton& skeleton,
                                          const TrainingOptions& options);
// The same from a prepared training set (e.g. MakeSequenceSet's); `split` names its data.
// InputError when its layer count is not the kind's.
std::unique_ptr<GaitModel> TrainGaitModel(TrainingSet set, const std::string& split,
                                          const ReferenceSkeleton& skeleton, const TrainingOptions& options);

}  // namespace jgpm
