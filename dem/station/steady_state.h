#pragma once
// Steady state of a DEM time series and the uncertainty of its mean, the way the LIGGGHTS rig
// did it (datasets/liggghts-rig/README.md "Steady state and averaging"):
//  1. block means of the series over `detect_block` (0.05 s) are compared with the mean of the last
//     `detect_tail` (0.4 s);
//  2. the steady window starts one block after the first block from which on every block mean stays
//     within max(10 %, 2.5 standard deviations of the tail's block means) of that reference;
//  3. the window is trimmed to a whole number of `mean_block` (0.1 s) blocks ending at the end of
//     the run;
//  4. the mean over the window, and its standard error from the `mean_block` block means,
//     sd(block means) / sqrt(blocks) (batch means; Flyvbjerg & Petersen 1989): the blocks are long
//     against the stream's correlation time (a particle crosses the rig in ~0.1 s).
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace chutelab::dem::station {

struct Estimate {
  double value = std::numeric_limits<double>::quiet_NaN();
  double se = std::numeric_limits<double>::quiet_NaN();  // standard error of the mean
  int n = 0;                                             // values (samples, particles) behind it
  bool ok() const { return std::isfinite(value); }
};

struct SteadyWindow {
  bool found = false;   // false: no steady state; the window is then the last mean blocks anyway
  double start = 0.0;   // s
  double end = 0.0;     // s
  int blocks = 0;       // whole mean_block blocks in [start, end]
};

struct SteadyParams {
  double detect_block = 0.05;
  double detect_tail = 0.4;
  double mean_block = 0.1;
  double relative_tolerance = 0.10;
  double sd_tolerance = 2.5;
};

// Samples are averages over consecutive intervals ending at t[k] (equal spacing).
SteadyWindow detect_steady(const std::vector<double>& t, const std::vector<double>& v, const SteadyParams& p);

// Weighted mean of values (t, v, w) with t in (start, end], and its standard error from the means
// of whole blocks of length `block` counted back from `end`. se is NaN with fewer than two blocks.
Estimate block_mean(const std::vector<double>& t, const std::vector<double>& v, const std::vector<double>& w,
                    double start, double end, double block);

// The ratio of two window means (e.g. moment / force) with the standard error from the block ratios.
Estimate block_ratio(const std::vector<double>& t, const std::vector<double>& num, const std::vector<double>& den,
                     double start, double end, double block);

// A straight line through the block means of (start, end]: its slope and the slope's standard
// error (NaN with fewer than three blocks), and the mean of the block means.
struct WindowTrend {
  double slope = std::numeric_limits<double>::quiet_NaN();     // per second
  double se_slope = std::numeric_limits<double>::quiet_NaN();
  double mean = std::numeric_limits<double>::quiet_NaN();
  double span = 0.0;  // end - start, s
  int blocks = 0;
  double change() const { return slope * span; }  // from the window's start to its end
  // The early stop's test: the change beyond max(rel * |mean|, 3 standard errors of it).
  bool drifting(double rel = 0.05) const {
    return blocks >= 3 && std::abs(slope * span) > std::max(rel * std::abs(mean), 3.0 * se_slope * span);
  }
};
WindowTrend window_trend(const std::vector<double>& t, const std::vector<double>& v, double start, double end,
                         double block);
// The same through the ratios of the two series' block means (e.g. an impact point, moment / force).
WindowTrend window_trend_ratio(const std::vector<double>& t, const std::vector<double>& num,
                               const std::vector<double>& den, double start, double end, double block);

// Does the window still drift? window_trend(...).drifting(rel).
bool drifting(const std::vector<double>& t, const std::vector<double>& v, double start, double end, double block,
              double rel = 0.05);

}  // namespace chutelab::dem::station
