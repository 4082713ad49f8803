// The pool behind the filter's per-particle work: every item is handed out exactly once, in
// chunks, to valid workers, for any item and thread count; an item's exception reaches the
// caller and the pool keeps working.
#include "tracker/filter/thread_pool.h"

#include <atomic>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

namespace jgpm {
namespace {

TEST(ThreadPool, EveryItemOnceToAValidWorker) {
  for (int threads : {1, 2, 3, 5}) {
    ThreadPool pool(threads);
    for (int n : {0, 1, 7, 200, 1001}) {
      std::vector<std::atomic<int>> seen(n);
      std::atomic<int> bad_worker{0}, bad_range{0};
      pool.For(n, [&](int begin, int end, int worker) {
        bad_worker += worker < 0 || worker >= pool.size();
        bad_range += begin < 0 || end > n || begin >= end;
        for (int i = begin; i < end; ++i) ++seen[i];
      });
      for (int i = 0; i < n; ++i) ASSERT_EQ(seen[i].load(), 1) << threads << " threads, item " << i << " of " << n;
      EXPECT_EQ(bad_worker.load(), 0);
      EXPECT_EQ(bad_range.load(), 0);
    }
  }
}

TEST(ThreadPool, AnItemsExceptionReachesTheCallerAndThePoolGoesOn) {
  ThreadPool pool(2);
  EXPECT_THROW(pool.For(100,
                        [](int begin, int end, int) {
                          for (int i = begin; i < end; ++i)
                            if (i == 77) throw std::runtime_error("item 77");
                        }),
               std::runtime_error);
  std::atomic<int> sum{0};
  pool.For(100, [&](int begin, int end, int) {
    for (int i = begin; i < end; ++i) sum += i;
  });
  EXPECT_EQ(sum.load(), 4950);
}

// A call returns once its items are done, while a worker woken late may still hold it: that
// worker must never run an old call's function (gone with its caller's frame) on a newer
// call's items. Many short calls back to back, each function with its own locals.
TEST(ThreadPool, BackToBackCallsEachRunTheirOwnFunction) {
  ThreadPool pool(2);
  std::atomic<int> current{-1}, foreign{0};
  for (int call = 0; call < 20000; ++call) {
    const int n = 1 + call % 9;
    std::vector<std::atomic<int>> seen(n);
    current = call;
    pool.For(n, [&, call](int begin, int end, int) {
      foreign += call != current;
      for (int i = begin; i < end; ++i) ++seen[i];
    });
    for (int i = 0; i < n; ++i) ASSERT_EQ(seen[i].load(), 1) << "call " << call << ", item " << i;
    ASSERT_EQ(foreign.load(), 0) << "call " << call;
  }
}

}  // namespace
}  // namespace jgpm
