#include "tracker/thread_pool.h"

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
    const int parts = size();
    try {
      (*job)(static_cast<int>(static_cast<long>(n) * worker / parts),
             static_cast<int>(static_cast<long>(n) * (worker + 1) / parts), worker);
    } catch (...) {
      errors_[worker] = std::current_exception();
    }
    {
      std::lock_guard<std::mutex> lock(mutex_);
      if (--pending_ == 0) done_.notify_one();
    }
  }
}

void ThreadPool::For(int n, const std::function<void(int begin, int end, int worker)>& fn) {
  std::fill(errors_.begin(), errors_.end(), nullptr);
  const int parts = size();
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
  try {
    fn(0, static_cast<int>(static_cast<long>(n) / parts), 0);
  } catch (...) {
    errors_[0] = std::current_exception();
  }
  if (parts > 1) {
    std::unique_lock<std::mutex> lock(mutex_);
    done_.wait(lock, [&] { return pending_ == 0; });
  }
  for (const std::exception_ptr& e : errors_)
    if (e) std::rethrow_exception(e);
}

}  // namespace jgpm
