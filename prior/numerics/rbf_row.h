// The squared-exponential kernel against many points, out_i = b1 exp(-b2/2 |x_i - q|^2):
// the innermost loop of training (kernel matrices), prediction and inference.
//
// It is the one place jgpm uses wide SIMD. The rest is built for baseline x86-64, like the
// Debian libraries it links: Eigen compiled for AVX allocates its blocks aligned past what
// malloc gives, and when such code shares a static link with Debian's Ceres (built for
// SSE2), the linker keeps one version of Eigen's inline allocator for both, so Ceres frees
// pointers it cannot (seen: heap corruption in Ceres's sparse Cholesky). This loop holds no
// Eigen type; GCC compiles it for AVX-512, AVX2 and baseline at once (target_clones) and
// the CPU picks at load time, with exp vectorised by glibc's libmvec. 1800 points: 1.9 us
// on AVX-512 against 10.6 us for Eigen's baseline exp.
#pragma once

namespace jgpm {

// `x` holds n points column-major (x[i], x[n + i], x[2n + i]); `q` one point; out: n values.
// Inputs must be finite.
void RbfRow(const double* x, int n, const double* q, double b1, double b2, double* out);

}  // namespace jgpm
