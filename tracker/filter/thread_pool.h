// A fixed set of worker threads for the particle filter's per-particle work. Work is split
// into contiguous chunks taken in turn by whichever worker is free; which worker computes an
// item never changes its result (each item's random numbers come from its own key,
// tracker/state/random.h, and its output has its own slot), only which scratch it uses.
#pragma once

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
  // the worker that threw takes no more chunks.
  void For(int n, const std::function<void(int begin, int end, int worker)>& fn);

 private:
  void Run(int worker);
  void Work(const std::function<void(int, int, int)>& fn, int n, int worker);

  std::vector<std::thread> workers_;
  std::mutex mutex_;
  std::condition_variable wake_, done_;
  const std::function<void(int, int, int)>* job_ = nullptr;
  int n_ = 0;
  long generation_ = 0;
  int pending_ = 0;
  int chunk_ = 1;
  std::atomic<int> next_{0};
  bool stop_ = false;
  std::vector<std::exception_ptr> errors_;
};

}  // namespace jgpm
