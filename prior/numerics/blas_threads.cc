#include "prior/numerics/blas_threads.h"

#include <algorithm>
#include <cstdlib>
#include <thread>

extern "C" void openblas_set_num_threads(int num_threads);
extern "C" int openblas_get_num_threads();

namespace jgpm {

int LinearAlgebraThreads() { return openblas_get_num_threads(); }

void UseOneLinearAlgebraThreadUnlessSet() {
  if (std::getenv("OPENBLAS_NUM_THREADS") == nullptr && std::getenv("OMP_NUM_THREADS") == nullptr)
    openblas_set_num_threads(1);
}

int ThreadsOrAllCores(int threads) {
  return threads > 0 ? threads : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
}

LinearAlgebraThreadScope::LinearAlgebraThreadScope(int threads) : previous_(LinearAlgebraThreads()) {
  if (threads > 0 && threads != previous_) openblas_set_num_threads(threads);
}

LinearAlgebraThreadScope::~LinearAlgebraThreadScope() {
  if (LinearAlgebraThreads() != previous_) openblas_set_num_threads(previous_);
}

}  // namespace jgpm
