#pragma once
// Where a rig's log is unloaded, loading, steady and unloading: found from the plate's load, never
// chosen by hand. The log is expected as a test engineer takes it: the zero with the belt empty,
// the stream starting, a steady run, the stream stopping, the zero again.
//
//  - The loaded part lies between the first and the last time the load (smoothed over a fifth of a
//    second) exceeds half its 95th percentile.
//  - Each of the three parts is judged steady by the project's one rule for time series
//    (dem/station/steady_state.h, detect_steady: block means against the mean of a steady tail).
//    The loaded part is cut in halves at its middle: the first half read forwards finds the end of
//    the start-up transient, the second half read backwards the start of the shut-down; the
//    unloaded part before is read backwards and the one after forwards, so that in each the tail
//    against which the blocks are judged is the part far from the load's change.
//  - The loaded window then starts as far again after the start-up transient as the rule found it
//    lasting, and ends as far again before the shut-down (steady_log.cpp says why).
#include <limits>
#include <string>
#include <vector>

#include "dem/station/steady_state.h"

namespace chutelab::logs {

struct Span {
  static constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  double start = nan, end = nan;  // s, samples with start < t <= end
  bool ok() const { return end > start; }
  double length() const { return ok() ? end - start : 0.0; }
  double centre() const { return 0.5 * (start + end); }
};

struct LogSegments {
  bool loaded = false;           // a loaded part at all
  double load_on = Span::nan;    // s, the load's first crossing of half its level
  double load_off = Span::nan;   // s, its last
  double load_start = Span::nan; // s, where the load leaves its zero before load_on (within 5 % of its level)
  Span before, after;            // the steady unloaded parts (tare); not ok() when absent
  Span window;                   // the steady loaded window
  bool steady = false;           // false: no steady state found; `window` is then the loaded part's middle half
  std::vector<std::string> warnings;
};

// The rule's parameters for a log sampled every `dt` seconds: blocks of 1 s (at least three
// samples: a gust of the stream lasting a fraction of a second is then not a block of its own); a
// block steady within 2 % of the tail's level or 3 standard deviations of the tail's block means (at
// 2.5, the DEM's, one block among a long log's many would end the transient late in one log of
// ten); the tail three quarters of the stretch judged, so that its spread is that of many blocks.
dem::station::SteadyParams log_steady_params(double dt, double tail);

// `t` equally spaced (s); `load` the plate's load in N with the layout's nominal zeros taken off.
LogSegments find_segments(const std::vector<double>& t, const std::vector<double>& load);

}  // namespace chutelab::logs
