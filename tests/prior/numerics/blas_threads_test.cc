// The OpenBLAS thread count: scopes restore the caller's count, and the `jgpm` command's
// starting count is one thread unless the user's environment names one.
#include "prior/numerics/blas_threads.h"

#include <cstdlib>

#include <gtest/gtest.h>

namespace jgpm {
namespace {

TEST(LinearAlgebraThreads, ScopesRestoreTheCallersCount) {
  const int before = LinearAlgebraThreads();
  {
    const LinearAlgebraThreadScope three(3);
    EXPECT_EQ(LinearAlgebraThreads(), 3);
    {
      const LinearAlgebraThreadScope unchanged(0);
      EXPECT_EQ(LinearAlgebraThreads(), 3);
    }
    EXPECT_EQ(LinearAlgebraThreads(), 3);
  }
  EXPECT_EQ(LinearAlgebraThreads(), before);
}

TEST(LinearAlgebraThreads, OneUnlessTheEnvironmentSaysOtherwise) {
  const LinearAlgebraThreadScope restore(0);  // whatever the test started with comes back
  unsetenv("OPENBLAS_NUM_THREADS");
  unsetenv("OMP_NUM_THREADS");
  {
    const LinearAlgebraThreadScope two(2);
    UseOneLinearAlgebraThreadUnlessSet();
    EXPECT_EQ(LinearAlgebraThreads(), 1);
  }
  for (const char* variable : {"OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS"}) {
    setenv(variable, "2", 1);
    const LinearAlgebraThreadScope two(2);
    UseOneLinearAlgebraThreadUnlessSet();
    EXPECT_EQ(LinearAlgebraThreads(), 2) << variable;
    unsetenv(variable);
  }
}

}  // namespace
}  // namespace jgpm
