// What `jgpm model info` and training summaries say about a model.
#pragma once

#include <string>

#include "prior/model/gait_model.h"

namespace jgpm {

// Mean 3-D joint position error (mm, over the 17 measured joints on the reference
// skeleton) between each training pose and the model's mean pose at its latent point: how
// well the model reproduces what it was trained on.
double TrainingReconstructionErrorMm(const GaitModel& model);

// A few lines describing a model: kind, data, hyper-parameters, training summary, latent
// extent and training reconstruction error.
std::string DescribeModel(const GaitModel& model);

}  // namespace jgpm
