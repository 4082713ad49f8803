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
  long seen = 0;
  for (;;) {
    const std::function<void(int, int, int)>* job;
    int n;
    {
      std::unique_lock<std::mutex> lock(mutex_);
      wake_.wait(lock, [&] { return stop_ || generation_ != seen; });
      if (stop_) return;
      seen = generation_;
      job = job_;
      n = n_;
    }
    Work(*job, n, worker);
    {
      std::lock_guard<std::mutex> lock(mutex_);
      if (--pending_ == 0) done_.notify_one();
    }
  }
}

void ThreadPool::Work(const std::function<void(int, int, int)>& fn, int n, int worker) {
  try {
    for (;;) {
      const int begin = next_.fetch_add(chunk_, std::memory_order_relaxed);
      if (begin >= n) return;
      fn(begin, std::min(n, begin + chunk_), worker);
    }
  } catch (...) {
    errors_[worker] = std::current_exception();
  }
}

void ThreadPool::For(int n, const std::function<void(int begin, int end, int worker)>& fn) {
  std::fill(errors_.begin(), errors_.end(), nullptr);
  const int parts = size();
  // Chunks of about a quarter of an even share: a worker whose items are cheap (bodies off
  // screen draw nothing) takes more of them.
  chunk_ = std::max(1, n / (4 * parts));
  next_.store(0, std::memory_order_relaxed);
  if (parts > 1) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      job_ = &fn;
      n_ = n;
      pending_ = parts - 1;
      ++generation_;
    }
    wake_.notify_all();
  }
  Work(fn, n, 0);
  if (parts > 1) {
    std::unique_lock<std::mutex> lock(mutex_);
    done_.wait(lock, [&] { return pending_ == 0; });
  }
  for (const std::exception_ptr& e : errors_)
    if (e) std::rethrow_exception(e);
}

}  // namespace jgpm
