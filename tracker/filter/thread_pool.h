// A fixed set of worker threads for the particle filter's per-particle work. Work is split
// into contiguous chunks taken in turn by whichever worker is free; which worker computes an
// item never changes its result (each item's random numbers come from its own key,
// tracker/state/random.h, and its output has its own slot), only which scratch it uses.
//
// A call returns when its items are done, not when every worker has looked in: a worker
// woken late (a sleeping thread takes a VM hundreds of microseconds to wake) finds the
// chunks taken and goes back to sleep, instead of holding up the caller, which had done
// them itself. (Waiting for every worker, a frame's 20-30 calls made 2 threads track
// 07_01-4cam only 1.6x as fast as one; the particles' prediction alone, 0.006 s over the
// clip on one thread, took 0.09 s on two.)
#pragma once

#include <cstdint>

#include <atomic>
#include <condition_variable>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace jgpm {

class ThreadPool {
 public:
  // `threads` workers in all (the calling thread is one of them); at least 1.
  explicit ThreadPool(int threads);
  ~ThreadPool();
  ThreadPool(const ThreadPool&) = delete;
  ThreadPool& operator=(const ThreadPool&) = delete;

  int size() const { return static_cast<int>(workers_.size()) + 1; }
  // Calls fn(begin, end, worker) for contiguous chunks covering [0, n) (each worker's calls
  // one at a time) and waits for all. An exception is rethrown here (the lowest worker's);
  // the worker that threw calls fn no more (the chunks it takes are skipped).
  void For(int n, const std::function<void(int begin, int end, int worker)>& fn);

 private:
  void Run(int worker);
  // Takes chunks of call `generation` until none is left (or a later call has begun).
  void Work(const std::function<void(int, int, int)>& fn, int n, int chunk, uint32_t generation, int worker);

  std::vector<std::thread> workers_;
  std::mutex mutex_;
  std::condition_variable wake_, done_;
  // The current call, read by a worker under the mutex when it wakes.
  const std::function<void(int, int, int)>* job_ = nullptr;
  int n_ = 0;
  int chunk_ = 1;
  uint32_t generation_ = 0;
  // The next item to hand out, with its call's generation in the high 32 bits, so that a
  // worker holding an old call's job never takes a newer call's items.
  std::atomic<uint64_t> next_{0};
  std::atomic<int> done_items_{0};
  bool stop_ = false;
  std::vector<std::exception_ptr> errors_;
};

}  // namespace jgpm
