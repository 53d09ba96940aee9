#pragma once
// A long call stopped by its caller: Python's Ctrl-C. (The command line needs none of this: a signal
// ends the process, core/output_folder.h.) The front end installs a check for the length of a call
// (Scope); the long loops pass interruption points: a DEM run between its force samples, a campaign
// between its jobs, side-by-side tasks between theirs, the harness between conditions. The check runs
// only on the thread that installed it (Python runs signal handlers on its main thread only), at
// most every 20 ms; the other threads see its verdict. Once it says stop, every point throws
// Interrupted, which unwinds the call like any error and leaves nothing half-written: outputs are
// written by the caller after the call returns, or staged (core/output_folder.h), and a DEM cache
// entry is written whole or not at all.
#include <atomic>
#include <functional>
#include <thread>
#include <vector>

namespace chutelab::interrupt {

// Not a std::exception: code that turns a failing step into "no value" (catch (const
// std::exception&)) must not turn a stop into one.
struct Interrupted {};

// While a Scope lives, `check` (true: stop) is asked at the points this thread passes. Scopes nest
// (the outermost one's check and thread are kept); a stop lasts until the outermost one ends.
class Scope {
 public:
  explicit Scope(std::function<bool()> check);
  ~Scope();
  Scope(const Scope&) = delete;
  Scope& operator=(const Scope&) = delete;
};

// Throws Interrupted once a stop was asked; on the checking thread, asks the check first.
void point();
// The checking thread's share of a wait for workers: asks the check and records a stop, never
// throws (the workers must finish before their caller may unwind).
void poll();
bool requested();
bool active();

// Joins `pool`, whose workers each add one to `finished` as their last act; meanwhile the checking
// thread keeps asking the check, so a stop is seen while the workers run (they stop at their next
// point).
void join(std::vector<std::thread>& pool, const std::atomic<std::size_t>& finished);

}  // namespace chutelab::interrupt
