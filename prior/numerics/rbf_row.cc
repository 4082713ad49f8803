// Built with -ffast-math (glibc declares its vector exp only then) and -fopenmp-simd; this
// file holds nothing else.
#include "prior/numerics/rbf_row.h"

#include <cmath>

namespace jgpm {

#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
__attribute__((target_clones("avx512f", "avx2,fma", "default")))
#endif
void RbfRow(const double* x, int n, const double* q, double b1, double b2, double* out) {
  const double* x0 = x;
  const double* x1 = x + n;
  const double* x2 = x + 2 * n;
  const double half_b2 = 0.5 * b2;
#pragma omp simd
  for (int i = 0; i < n; ++i) {
    const double a = x0[i] - q[0], b = x1[i] - q[1], c = x2[i] - q[2];
    out[i] = b1 * std::exp(-half_b2 * (a * a + b * b + c * c));
  }
}

}  // namespace jgpm
