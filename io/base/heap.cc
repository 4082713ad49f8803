#include "io/base/heap.h"

#include <malloc.h>

#include <cstddef>

namespace jgpm {

constexpr std::size_t kHeapTrimThreshold = std::size_t{1} << 30;

bool KeepFreedMemory() {
  // A threshold alone cannot do it: glibc caps M_MMAP_THRESHOLD at 32 MB, and an exact
  // objective at N = 3600 has 104 MB matrices. Setting the trim threshold also turns off
  // glibc's dynamic adjustment of both thresholds.
  const bool mmap_ok = mallopt(M_MMAP_MAX, 0) == 1;
  const bool trim_ok = mallopt(M_TRIM_THRESHOLD, static_cast<int>(kHeapTrimThreshold)) == 1;
  return mmap_ok && trim_ok;
}

}  // namespace jgpm
