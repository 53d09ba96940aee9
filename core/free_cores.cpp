#include "core/free_cores.h"

#include <algorithm>
#include <cmath>
#include <ctime>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <thread>

namespace chutelab {
namespace {

// Busy jiffies of the whole machine (/proc/stat's first line), niced time and idle/iowait left out.
std::optional<double> busy_ticks() {
  std::ifstream in("/proc/stat");
  std::string cpu;
  double user = 0, nice = 0, system = 0, idle = 0, iowait = 0, irq = 0, softirq = 0, steal = 0;
  if (!(in >> cpu >> user >> nice >> system >> idle >> iowait >> irq >> softirq >> steal) || cpu != "cpu")
    return std::nullopt;
  return user + system + irq + softirq + steal;
}

double own_cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

}  // namespace

double busy_cores_of_others(std::chrono::milliseconds window) {
  const double ticks_per_s = 100.0;  // USER_HZ: /proc/stat's unit on every Linux ABI
  const auto a = busy_ticks();
  const double own_a = own_cpu_seconds();
  const auto t0 = std::chrono::steady_clock::now();
  std::this_thread::sleep_for(window);
  const auto b = busy_ticks();
  const double own_b = own_cpu_seconds();
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (!a || !b || !(seconds > 0.0)) return 0.0;
  const double others = (*b - *a) / ticks_per_s - (own_b - own_a);
  return std::max(0.0, others / seconds);
}

int free_cores() {
  const int cores = std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
  const int busy = static_cast<int>(std::lround(busy_cores_of_others()));
  return std::clamp(cores - busy, 1, cores);
}

}  // namespace chutelab
