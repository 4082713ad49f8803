#include "prior/learning/training_progress.h"

#include <cmath>
#include <cstdio>
#include <limits>

#include "io/base/enum_name.h"

namespace jgpm {

std::string_view LearningName(Learning learning) {
  switch (learning) {
    case Learning::kClosedForm: return "closed form";
    case Learning::kFull: return "full";
    case Learning::kLocal: return "local";
    case Learning::kSparse: return "sparse";
  }
  return "?";
}

bool ParseLearning(std::string_view name, Learning* learning) {
  return ParseByName(name, {Learning::kClosedForm, Learning::kFull, Learning::kLocal, Learning::kSparse},
                     LearningName, learning);
}

double WindowImprovement(const std::vector<double>& history, int window) {
  if (window < 1 || static_cast<int>(history.size()) <= window) return std::numeric_limits<double>::quiet_NaN();
  return (history[history.size() - 1 - window] - history.back()) / std::abs(history.back());
}

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
                std::string(LearningName(learning)).c_str(), how.c_str(), iterations, initial_objective,
                final_objective, max_jitter, wall_seconds);
  if (inducing > 0) {
    char exact[128];
    std::snprintf(exact, sizeof(exact), "; %d inducing inputs, exact objective %.6g", inducing, exact_objective);
    return line + std::string(exact);
  }
  return line;
}

}  // namespace jgpm
