#pragma once
// The mean of a window of correlated samples and its honest standard uncertainty.
//
// A logged force is not a set of independent readings: the stream, the plate's vibration and the
// logger's own filter make neighbouring samples alike, so sd/sqrt(n) is too small by the square root
// of twice the integrated autocorrelation time in samples. The uncertainty here is that of batch
// means (dem/station/steady_state.h, Flyvbjerg & Petersen 1989), with the batch length chosen from
// the series' own autocorrelation time (Sokal's self-consistent window), so that the batches are
// nearly independent:
//  - blocks of kBlocksPerTau integrated autocorrelation times;
//  - neighbouring blocks of an exponentially correlated series still correlate by rho_1 (below): the
//    variance of the mean is widened by (1 + 2 rho_1) for it;
//  - the standard error from b blocks is itself uncertain with b - 1 degrees of freedom; the dof
//    travel with it so that the combined uncertainty can be widened as a t-distribution's
//    (uncertainty_budget.h), never silently small.
#include <limits>
#include <vector>

namespace chutelab::logs {

// How long a series remembers, in samples, its linear trend removed first (a trend is not noise: it
// is tested on its own, log_reading.h):
//  - integrated: 1/2 + the sum of the normalised autocorrelation up to the smallest window M with
//    M >= 5 tau (Sokal 1997); 1/2 for white noise;
//  - e_fold: the lag at which the autocorrelation has fallen to 1/e of its value at lag 1, the
//    correlation time of the series' slow part even under a floor of white noise (which shortens
//    the integrated time without making the slow part any faster).
// Both are divided by (1 - 12 tau / n): a window of n samples sees that much less than the truth
// (the mean and line removed, the sum cut at M; measured on AR(1) series, tests/logs).
struct Correlation {
  double integrated = 0.5, e_fold = 0.0, window = 0.0;
};
Correlation correlation_times(const std::vector<double>& x);
double autocorrelation_time(const std::vector<double>& x);  // correlation_times(x).integrated

// Batch length, in samples, for a series of integrated autocorrelation time `tau` samples.
inline constexpr double kBlocksPerTau = 6.0;
// At most this many batches a window (fewer when the correlation time asks for longer ones).
inline constexpr double kMaxBlocks = 8.0;
// Fewer batches than this: the standard error from the autocorrelation time instead.
inline constexpr int kMinBlocks = 4;

// Correlation of the means of two neighbouring blocks of `block` samples of a series with an
// exponential autocorrelation of integrated time `tau` samples (both > 0).
double neighbour_block_correlation(double tau, double block);

struct CorrelatedMean {
  static constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  double mean = nan;
  double sd = nan;          // of the samples, about the window's line (trend removed)
  int n = 0;                // samples in the window
  double tau = nan;         // s, integrated autocorrelation time
  double n_eff = nan;       // n / (2 tau / dt): independent samples the window is worth
  double block = nan;       // s, batch length
  int blocks = 0;
  double rho1 = 0.0;        // correlation of neighbouring batch means (the widening's reason)
  double se = nan;          // standard error of the mean (widened for rho1)
  double dof = 0.0;         // of se: blocks - 1 (blocks - 2 when the trend was removed)
  // The trend through the window's samples (per second), its standard error (the larger of the
  // batch means' line's and the correlated samples') and degrees of freedom: the creep test's.
  double slope = nan, se_slope = nan, slope_dof = 1.0;
  bool ok() const { return blocks >= 2 && se == se; }
};

// Samples (t, v) with t in (start, end]; equally spaced. `detrend`: the batch means' scatter is
// taken about their straight line rather than their mean (a creep that will be corrected: the
// standard error is then that of the line's value at the window's centre).
CorrelatedMean correlated_mean(const std::vector<double>& t, const std::vector<double>& v, double start,
                               double end, bool detrend = false);

}  // namespace chutelab::logs
