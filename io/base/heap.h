// Keeping freed memory for reuse instead of returning it to the system (process-wide).
//
// Learning and tracking allocate the same large temporaries (N x M kernel matrices,
// N x N factors, frame buffers) on every evaluation. glibc serves blocks above its mmap
// threshold (128 kB at first) with a fresh mmap and unmaps them when freed, and trims the
// heap's top above its trim threshold, so every evaluation page-faults its temporaries in
// again. On our virtual machines a page fault is expensive: a sparse objective evaluation
// (N = 1800, M = 100) spent most of its time in the kernel's page-fault path and ran 4-7x
// slower than with the memory kept (measured side by side, `jgpm bench learning`).
#pragma once

namespace jgpm {

// Every block comes from the heap (no mmap of single blocks; glibc still maps memory when
// the heap cannot grow), and freed heap memory is kept up to 1 GB. Call once at the start
// of main, before threads exist. Returns false if the C library refused (the program
// still works, only slower).
bool KeepFreedMemory();

}  // namespace jgpm
