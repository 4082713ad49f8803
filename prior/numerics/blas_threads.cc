#include "prior/numerics/blas_threads.h"

#include <cstdlib>

extern "C" void openblas_set_num_threads(int num_threads);
extern "C" int openblas_get_num_threads();

namespace jgpm {

int LinearAlgebraThreads() { return openblas_get_num_threads(); }

void UseOneLinearAlgebraThreadUnlessSet() {
  if (std::getenv("OPENBLAS_NUM_THREADS") == nullptr && std::getenv("OMP_NUM_THREADS") == nullptr)
    openblas_set_num_threads(1);
}

LinearAlgebraThreadScope::LinearAlgebraThreadScope(int threads) : previous_(LinearAlgebraThreads()) {
  if (threads > 0 && threads != previous_) openblas_set_num_threads(threads);
}

LinearAlgebraThreadScope::~LinearAlgebraThreadScope() {
  if (LinearAlgebraThreads() != previous_) openblas_set_num_threads(previous_);
}

}  // namespace jgpm
