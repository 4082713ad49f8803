// How an optimisation ended: training (full, local, sparse), the chain least-squares
// solver and the sequence inference built on it.
#pragma once

#include <string_view>

namespace jgpm {

enum class Termination {
  kConverged,        // the stopping rule was met
  kNoConvergence,    // iteration cap
  kStopped,          // time budget or interrupt
  kNumericalFailure, // no step could be evaluated (non-finite values, no factorisation)
};

// "converged", "no convergence", "stopped", "numerical failure" (as in model files).
std::string_view TerminationName(Termination termination);
bool ParseTermination(std::string_view name, Termination* termination);

}  // namespace jgpm
