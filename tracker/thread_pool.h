// A fixed set of worker threads for the particle filter's per-particle work. Work is split
// into contiguous ranges by index, one per worker, so which worker computes an item never
// changes its result (each item's random numbers come from its own key, tracker/random.h).
#pragma once

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
  // Calls fn(begin, end, worker) for `size()` contiguous ranges covering [0, n) and waits
  // for all. An exception in any range is rethrown here (the first range's first).
  void For(int n, const std::function<void(int begin, int end, int worker)>& fn);

 private:
  void Run(int worker);

  std::vector<std::thread> workers_;
  std::mutex mutex_;
  std::condition_variable wake_, done_;
  const std::function<void(int, int, int)>* job_ = nullptr;
  int n_ = 0;
  long generation_ = 0;
  int pending_ = 0;
  bool stop_ = false;
  std::vector<std::exception_ptr> errors_;
};

}  // namespace jgpm
