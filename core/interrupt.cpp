#include "core/interrupt.h"

#include <chrono>
#include <mutex>

namespace chutelab::interrupt {
namespace {

std::mutex g_mutex;
int g_depth = 0;
std::function<bool()> g_check;             // set and read on the checking thread only, while active
std::atomic<std::thread::id> g_checker{};
std::atomic<bool> g_active{false}, g_stop{false};
std::chrono::steady_clock::time_point g_last{};  // the checking thread's last check

constexpr auto kEvery = std::chrono::milliseconds(20);

}  // namespace

Scope::Scope(std::function<bool()> check) {
  const std::lock_guard<std::mutex> lock(g_mutex);
  if (g_depth++ > 0) return;
  g_check = std::move(check);
  g_last = {};
  g_stop = false;
  g_checker = std::this_thread::get_id();
  g_active = true;
}

Scope::~Scope() {
  const std::lock_guard<std::mutex> lock(g_mutex);
  if (--g_depth > 0) return;
  g_active = false;
  g_checker = std::thread::id{};
  g_check = nullptr;
  g_stop = false;
}

void poll() {
  if (!g_active.load(std::memory_order_acquire) || g_stop.load(std::memory_order_relaxed)) return;
  if (g_checker.load(std::memory_order_relaxed) != std::this_thread::get_id()) return;
  const auto now = std::chrono::steady_clock::now();
  if (now - g_last < kEvery) return;
  g_last = now;
  if (g_check && g_check()) g_stop = true;
}

void point() {
  poll();
  if (g_stop.load(std::memory_order_relaxed)) throw Interrupted();
}

bool requested() { return g_stop.load(); }
bool active() { return g_active.load(); }

void join(std::vector<std::thread>& pool, const std::atomic<std::size_t>& finished) {
  if (g_active.load() && g_checker.load() == std::this_thread::get_id())
    while (finished.load() < pool.size()) {
      poll();
      std::this_thread::sleep_for(kEvery);
    }
  for (auto& t : pool) t.join();
}

}  // namespace chutelab::interrupt
