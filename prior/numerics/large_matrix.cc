#include "prior/numerics/large_matrix.h"

#include <sys/mman.h>

#include <cstdint>

namespace jgpm {

Eigen::MatrixXd LargeMatrix(Eigen::Index rows, Eigen::Index cols) {
  Eigen::MatrixXd m(rows, cols);
  constexpr uintptr_t kHugePage = uintptr_t{2} << 20;
  const uintptr_t begin = reinterpret_cast<uintptr_t>(m.data());
  const uintptr_t end = begin + static_cast<uintptr_t>(m.size()) * sizeof(double);
  if (end - begin >= 2 * kHugePage) {
    // madvise needs page-aligned ranges; the whole huge pages inside the block are what
    // can be given anyway. A refusal (no THP) leaves the matrix as it is.
    const uintptr_t first = (begin + kHugePage - 1) & ~(kHugePage - 1), last = end & ~(kHugePage - 1);
    if (last > first) madvise(reinterpret_cast<void*>(first), last - first, MADV_HUGEPAGE);
  }
  return m;
}

}  // namespace jgpm
