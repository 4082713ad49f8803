#include "prior/numerics/termination.h"

#include "io/base/enum_name.h"

namespace jgpm {

std::string_view TerminationName(Termination termination) {
  switch (termination) {
    case Termination::kConverged: return "converged";
    case Termination::kNoConvergence: return "no convergence";
    case Termination::kStopped: return "stopped";
    case Termination::kNumericalFailure: return "numerical failure";
  }
  return "?";
}

bool ParseTermination(std::string_view name, Termination* termination) {
  return ParseByName(name,
                     {Termination::kConverged, Termination::kNoConvergence, Termination::kStopped,
                      Termination::kNumericalFailure},
                     TerminationName, termination);
}

}  // namespace jgpm
