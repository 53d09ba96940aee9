#include "core/worker_pool.h"

#include <chrono>

namespace chutelab {

WorkerPool::WorkerPool(int workers) {
  for (int i = 0; i < workers; ++i) threads_.emplace_back([this] { loop(); });
}

WorkerPool::~WorkerPool() {
  {
    const std::lock_guard<std::mutex> lock(m_);
    stop_ = true;
    posted_.store(~std::uint64_t{0}, std::memory_order_release);
  }
  wake_.notify_all();
  for (auto& t : threads_) t.join();
}

void WorkerPool::run(const std::function<void()>& work) {
  {
    const std::lock_guard<std::mutex> lock(m_);
    work_ = &work;
    running_ = workers();
    posted_.store(++generation_, std::memory_order_release);
  }
  wake_.notify_all();
  work();
  std::unique_lock<std::mutex> lock(m_);
  done_.wait(lock, [this] { return running_ == 0; });
  work_ = nullptr;
}

void WorkerPool::loop() {
  std::uint64_t seen = 0;
  while (true) {
    // Evaluations come in quick succession: look for the next for a fifth of a millisecond before
    // sleeping, which costs a wake-up of the same order.
    const auto until = std::chrono::steady_clock::now() + std::chrono::microseconds(200);
    while (posted_.load(std::memory_order_acquire) == seen && std::chrono::steady_clock::now() < until)
      std::this_thread::yield();
    std::unique_lock<std::mutex> lock(m_);
    wake_.wait(lock, [&] { return stop_ || generation_ != seen; });
    if (stop_) return;
    seen = generation_;
    const std::function<void()>* work = work_;
    lock.unlock();
    (*work)();
    lock.lock();
    if (--running_ == 0) done_.notify_one();
  }
}

}  // namespace chutelab
