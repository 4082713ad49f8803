#include "prior/training_progress.h"

#include <cstdio>

namespace jgpm {

std::string TrainingBudget::Exhausted(double elapsed_seconds) const {
  if (interrupted && interrupted->load()) return "interrupted";
  if (max_seconds > 0 && elapsed_seconds >= max_seconds) {
    char why[64];
    std::snprintf(why, sizeof(why), "time budget of %g s used up", max_seconds);
    return why;
  }
  return "";
}

std::string TrainingSummary::BriefReport() const {
  char line[512];
  const std::string name(TerminationName(termination));
  const std::string how = termination == Termination::kStopped ||
                                  termination == Termination::kNumericalFailure
                              ? name + " (" + message + ")"
                              : name;
  std::snprintf(line, sizeof(line),
                "%s learning: %s after %d iterations, objective %.6g -> %.6g, max jitter %.2g, "
                "%.1f s",
                learning.c_str(), how.c_str(), iterations, initial_objective,
                final_objective, max_jitter, wall_seconds);
  if (inducing > 0) {
    char exact[128];
    std::snprintf(exact, sizeof(exact), "; %d inducing inputs, exact objective %.6g", inducing, exact_objective);
    return line + std::string(exact);
  }
  return line;
}

}  // namespace jgpm
