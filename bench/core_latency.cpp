// How long a cache line takes to go from one core to the other and back: two threads hand a
// counter back and forth. The DEM's 2-thread speed-up depends on it (threads share particle
// state at their ranges' edges and meet at barriers), and on a VM it changes with where the host
// places the virtual CPUs, so bench/dem_vs_liggghts prints it beside every speed-up.
// Usage: core_latency [round trips]   Prints: core_round_trip_ns=X
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <thread>

int main(int argc, char** argv) {
  const long n = argc > 1 ? std::atol(argv[1]) : 1000000;
  if (n <= 0) {
    std::fprintf(stderr, "core_latency: the number of round trips must be a positive integer\n");
    return 2;
  }
  if (std::thread::hardware_concurrency() < 2) {  // two spinning threads on one core would take turns by time slice
    std::printf("core_round_trip_ns=n/a (one CPU)\n");
    return 0;
  }
  alignas(64) std::atomic<long> token{0};
  const auto t0 = std::chrono::steady_clock::now();
  std::thread other([&] {
    for (long i = 0; i < n; ++i) {
      while (token.load(std::memory_order_acquire) != 2 * i + 1) {
      }
      token.store(2 * i + 2, std::memory_order_release);
    }
  });
  for (long i = 0; i < n; ++i) {
    while (token.load(std::memory_order_acquire) != 2 * i) {
    }
    token.store(2 * i + 1, std::memory_order_release);
  }
  other.join();
  const double ns = std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - t0).count();
  std::printf("core_round_trip_ns=%.0f\n", ns / static_cast<double>(n));
  return 0;
}
