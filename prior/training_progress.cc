#include "prior/training_progress.h"

#include <cstdio>

namespace jgpm {

std::string TrainingSummary::BriefReport() const {
  char line[512];
  std::snprintf(line, sizeof(line),
                "%s learning: %s after %d iterations, objective %.6g -> %.6g, max jitter %.2g, "
                "%.1f s",
                learning.c_str(), termination.c_str(), iterations, initial_objective,
                final_objective, max_jitter, wall_seconds);
  return line;
}

}  // namespace jgpm
