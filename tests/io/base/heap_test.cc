// KeepFreedMemory (io/base/heap.h) against what glibc reports (mallinfo2): large blocks come
// from the heap, which keeps them when they are freed, so the next ones need no new pages.
#include "io/base/heap.h"

#include <malloc.h>

#include <cstdlib>
#include <cstring>

#include <gtest/gtest.h>

namespace jgpm {
namespace {

// Touches every page so that the allocation cannot be optimised away.
void* Use(std::size_t bytes) {
  void* p = std::malloc(bytes);
  std::memset(p, 1, bytes);
  return p;
}

#if defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer) || __has_feature(memory_sanitizer)
#define JGPM_SANITIZED_HEAP 1
#endif
#endif
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
#define JGPM_SANITIZED_HEAP 1
#endif

TEST(Heap, LargeBlocksComeFromTheHeapAndStayThere) {
#ifdef JGPM_SANITIZED_HEAP
  GTEST_SKIP() << "a sanitizer's allocator replaces glibc's";
#endif
  // In a fresh process glibc would mmap each of these (its threshold starts at 128 kB) and
  // trim the heap's top once they are freed.
  ASSERT_TRUE(KeepFreedMemory());
  constexpr std::size_t kBlock = std::size_t{4} << 20;
  constexpr int kBlocks = 8;
  const std::size_t mapped = mallinfo2().hblkhd;
  void* blocks[kBlocks];
  for (void*& b : blocks) b = Use(kBlock);
  EXPECT_EQ(mallinfo2().hblkhd, mapped) << "no block was mmapped";
  const std::size_t arena = mallinfo2().arena;
  EXPECT_GE(arena, kBlocks * kBlock);
  for (void* b : blocks) std::free(b);
  EXPECT_EQ(mallinfo2().arena, arena) << "the heap was trimmed";
  EXPECT_GE(mallinfo2().fordblks, kBlocks * kBlock) << "the freed blocks are kept for reuse";
  for (void*& b : blocks) b = Use(kBlock);
  EXPECT_EQ(mallinfo2().arena, arena) << "the second round reuses the first's memory";
  for (void* b : blocks) std::free(b);
  // Beyond glibc's largest mmap threshold (32 MB) too.
  void* large = Use(std::size_t{96} << 20);
  EXPECT_EQ(mallinfo2().hblkhd, mapped) << "a 96 MB block was mmapped";
  std::free(large);
}

}  // namespace
}  // namespace jgpm
