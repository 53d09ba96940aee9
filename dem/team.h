#pragma once
// How the engine's passes run on a team of threads (OpenMP), and when they run without one.
#include <omp.h>

#include <cstddef>
#include <utility>

namespace chutelab::dem {

// Whether a pass asked for nt threads runs on the calling thread, outside any OpenMP region.
// libgomp ends every region, and every barrier in it, with a futex wake even in a team of one,
// where no thread can be waiting: a system call, about six per step, which on this project's VM took
// 5-7 % of a one-thread station run (bench/log/RESULTS.md). Outside a region omp_get_thread_num() is 0,
// omp_get_num_threads() 1 and an orphaned barrier returns at once, so the body does exactly what it
// did in a team of one. Inside someone else's region (level > 0) an orphaned barrier would bind to
// their team, so there the pass keeps its own region.
inline bool runs_alone(int nt) { return nt <= 1 && omp_get_level() == 0; }

// body() once on each of nt threads, or once here when runs_alone(nt).
template <class F>
void on_team(int nt, F&& body) {
  if (runs_alone(nt)) {
    body();
    return;
  }
#pragma omp parallel num_threads(nt)
  body();
}

// Thread t's even share [first, last) of n items cut among nt threads. The cut depends only on
// (n, t, nt), so passes that cut the same n the same way hand each thread the same items.
inline std::pair<std::size_t, std::size_t> even_share(std::size_t n, std::size_t t, std::size_t nt) {
  return {n * t / nt, n * (t + 1) / nt};
}

}  // namespace chutelab::dem
