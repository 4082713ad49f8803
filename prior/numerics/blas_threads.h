// The OpenBLAS thread count: one process-wide setting, owned by scopes. Whoever needs a
// count for a while (training: `--threads`; local learning: one thread for its small
// steps; validation: one per worker because the trials run in parallel) holds a scope,
// and the caller's count comes back when it ends, so no call leaves the process changed.
// Only the thread that runs the job creates scopes; worker threads never do.
#pragma once

namespace jgpm {

// Threads OpenBLAS uses now.
int LinearAlgebraThreads();

// One thread unless the user set OPENBLAS_NUM_THREADS or OMP_NUM_THREADS: the `jgpm`
// command's starting count. Why: OpenBLAS starts a thread per core, and between calls its
// idle threads spin on sched_yield. Outside training jgpm's matrices are a few hundred
// wide, too small for a second thread to gain, so the spinning only took the other core:
// `jgpm eval --suite transitions` on one event took 2.01 s with OpenBLAS's two threads and
// 1.22 s with one (Release), 27.8 s and 6.5 s under the sanitizers, and several times as
// long when another process wanted the core. Training, where the kernels are larger, keeps
// all cores by default (`train --threads`; 5% faster with 2 than 1 on the training split).
// Not in the Python module: there OpenBLAS may be NumPy's too, and is not ours to set.
void UseOneLinearAlgebraThreadUnlessSet();

// Training's count for a `--threads` value: itself, or every core for 0 (what `jgpm train`
// and Python's train use, so that both factorise alike).
int ThreadsOrAllCores(int threads);

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
