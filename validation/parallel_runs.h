#pragma once
// Independent expensive runs (DEM signatures, confirmations) side by side in one process: `jobs`
// worker threads take the tasks in order. Each task writes only its own, pre-created result slot,
// so the outcome does not depend on which worker ran what. The first failure (in task order) is
// rethrown once every worker has stopped; a stop asked by the caller (core/interrupt.h) before any.
#include <algorithm>
#include <atomic>
#include <exception>
#include <functional>
#include <thread>
#include <vector>

#include "core/interrupt.h"

namespace chutelab::validation {

inline void run_concurrently(const std::vector<std::function<void()>>& tasks, int jobs) {
  if (tasks.empty()) return;
  const std::size_t n = tasks.size();
  const std::size_t workers = std::clamp<std::size_t>(jobs > 0 ? static_cast<std::size_t>(jobs) : 1, 1, n);
  std::vector<std::exception_ptr> failure(n);
  if (workers == 1) {
    for (std::size_t i = 0; i < n; ++i) try {
        interrupt::point();
        tasks[i]();
      } catch (...) {
        failure[i] = std::current_exception();
      }
  } else {
    std::atomic<std::size_t> next{0}, finished{0};
    std::vector<std::thread> pool;
    for (std::size_t w = 0; w < workers; ++w)
      pool.emplace_back([&] {
        for (std::size_t i; (i = next.fetch_add(1)) < n;) try {
            interrupt::point();
            tasks[i]();
          } catch (...) {
            failure[i] = std::current_exception();
          }
        finished.fetch_add(1);
      });
    interrupt::join(pool, finished);
  }
  if (interrupt::requested()) throw interrupt::Interrupted();
  for (const auto& f : failure)
    if (f) std::rethrow_exception(f);
}

}  // namespace chutelab::validation
