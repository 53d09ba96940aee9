#pragma once
// Threads kept for short parallel sections. A fit evaluates its cost thousands of times, often on a
// sample of a few hundred conditions that takes about a millisecond: a thread started per
// evaluation was still starting while the caller did most of the work (the caller ran three
// quarters of the conditions on two cores). Kept workers wait a moment spinning, then sleep.
#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace chutelab {

class WorkerPool {
 public:
  explicit WorkerPool(int workers);
  ~WorkerPool();
  WorkerPool(const WorkerPool&) = delete;
  WorkerPool& operator=(const WorkerPool&) = delete;

  int workers() const { return static_cast<int>(threads_.size()); }
  // Runs `work` on every worker and on the calling thread and returns when all have returned.
  // `work` shares the tasks out itself (an atomic counter) and must not throw. One run at a time.
  void run(const std::function<void()>& work);

 private:
  void loop();

  std::mutex m_;
  std::condition_variable wake_, done_;
  const std::function<void()>* work_ = nullptr;
  std::uint64_t generation_ = 0;
  std::atomic<std::uint64_t> posted_{0};  // generation_, read without the lock while spinning
  int running_ = 0;
  bool stop_ = false;
  std::vector<std::thread> threads_;
};

}  // namespace chutelab
