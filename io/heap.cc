#include "io/heap.h"

#include <malloc.h>

namespace jgpm {

bool KeepFreedMemory() {
  // Setting either turns off glibc's dynamic adjustment of both, which is what is wanted:
  // fixed, generous thresholds.
  const bool mmap_ok = mallopt(M_MMAP_THRESHOLD, static_cast<int>(kHeapMmapThreshold)) == 1;
  const bool trim_ok = mallopt(M_TRIM_THRESHOLD, static_cast<int>(kHeapTrimThreshold)) == 1;
  return mmap_ok && trim_ok;
}

}  // namespace jgpm
