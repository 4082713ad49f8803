#include "tracker/filter/thread_pool.h"

#include <algorithm>

namespace jgpm {

ThreadPool::ThreadPool(int threads) {
  const int n = std::max(1, threads);
  errors_.resize(n);
  for (int w = 1; w < n; ++w) workers_.emplace_back(&ThreadPool::Run, this, w);
}

ThreadPool::~ThreadPool() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  for (std::thread& t : workers_) t.join();
}

void ThreadPool::Run(int worker) {
  uint32_t seen = 0;
  for (;;) {
    const std::function<void(int, int, int)>* job;
    int n, chunk;
    {
      std::unique_lock<std::mutex> lock(mutex_);
      wake_.wait(lock, [&] { return stop_ || generation_ != seen; });
      if (stop_) return;
      seen = generation_;
      job = job_;
      n = n_;
      chunk = chunk_;
    }
    // `job` is called only for a chunk of call `seen` taken from next_, and that call
    // waits for its chunks, so the function is still there.
    Work(*job, n, chunk, seen, worker);
  }
}

void ThreadPool::Work(const std::function<void(int, int, int)>& fn, int n, int chunk, uint32_t generation,
                      int worker) {
  bool failed = false;
  for (;;) {
    uint64_t next = next_.load();
    int begin;
    do {
      begin = static_cast<int>(next & 0xffffffffu);
      if (next >> 32 != generation || begin >= n) return;
    } while (!next_.compare_exchange_weak(next, next + chunk));
    const int end = std::min(n, begin + chunk);
    if (!failed) {
      try {
        fn(begin, end, worker);
      } catch (...) {
        errors_[worker] = std::current_exception();
        failed = true;
      }
    }
    if (done_items_.fetch_add(end - begin) + (end - begin) == n) {
      std::lock_guard<std::mutex> lock(mutex_);
      done_.notify_one();
    }
  }
}

void ThreadPool::For(int n, const std::function<void(int begin, int end, int worker)>& fn) {
  std::fill(errors_.begin(), errors_.end(), nullptr);
  const int parts = size();
  // Chunks of about a quarter of an even share: a worker whose items are cheap (bodies off
  // screen draw nothing) takes more of them.
  const int chunk = std::max(1, n / (4 * parts));
  uint32_t generation;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    generation = ++generation_;
    job_ = &fn;
    n_ = n;
    chunk_ = chunk;
    done_items_.store(0);
    next_.store(uint64_t{generation} << 32);
  }
  if (parts > 1 && n > chunk) wake_.notify_all();
  Work(fn, n, chunk, generation, 0);
  {
    std::unique_lock<std::mutex> lock(mutex_);
    done_.wait(lock, [&] { return done_items_.load() >= n; });
  }
  for (const std::exception_ptr& e : errors_)
    if (e) std::rethrow_exception(e);
}

}  // namespace jgpm
