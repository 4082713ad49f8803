// The OpenBLAS thread count: one process-wide setting, owned by scopes. Whoever needs a
// count for a while (training: `--threads`; local learning: one thread for its small
// steps; validation: one per worker because the trials run in parallel) holds a scope,
// and the caller's count comes back when it ends, so no call leaves the process changed.
// Only the thread that runs the job creates scopes; worker threads never do.
#pragma once

namespace jgpm {

// Threads OpenBLAS uses now.
int LinearAlgebraThreads();

// Sets the OpenBLAS thread count while in scope (0: leave it as it is) and restores the
// previous one after.
class LinearAlgebraThreadScope {
 public:
  explicit LinearAlgebraThreadScope(int threads);
  ~LinearAlgebraThreadScope();
  LinearAlgebraThreadScope(const LinearAlgebraThreadScope&) = delete;
  LinearAlgebraThreadScope& operator=(const LinearAlgebraThreadScope&) = delete;

 private:
  int previous_;
};

}  // namespace jgpm
