#include "logs/correlated_mean.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "dem/station/steady_state.h"

namespace chutelab::logs {

Correlation correlation_times(const std::vector<double>& x) {
  Correlation out;
  const std::size_t n = x.size();
  if (n < 4) return out;
  // Residuals about the least-squares line through (k, x_k).
  double km = 0.5 * static_cast<double>(n - 1), xm = 0.0;
  for (double v : x) xm += v;
  xm /= static_cast<double>(n);
  double sxx = 0.0, sxy = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    sxx += (static_cast<double>(k) - km) * (static_cast<double>(k) - km);
    sxy += (static_cast<double>(k) - km) * (x[k] - xm);
  }
  const double slope = sxy / sxx;
  std::vector<double> r(n);
  for (std::size_t k = 0; k < n; ++k) r[k] = x[k] - xm - slope * (static_cast<double>(k) - km);
  double c0 = 0.0;
  for (double v : r) c0 += v * v;
  if (!(c0 > 0.0)) return out;
  // Sokal's window: the sum up to the first M >= 5 tau(M). Lags beyond n/4 say too little.
  double tau = 0.5, rho1 = 0.0, prev = 1.0;
  double e_fold = 0.0;
  const std::size_t max_lag = n / 4;
  std::size_t m = 1;
  for (; m <= max_lag; ++m) {
    double c = 0.0;
    for (std::size_t k = 0; k + m < n; ++k) c += r[k] * r[k + m];
    const double rho = c / c0;
    if (m == 1) rho1 = rho;
    // Where the correlation has fallen to 1/e of its first lag's: the slow part's own time, which
    // a white-noise floor hides in the integrated time.
    if (e_fold == 0.0 && rho1 > 0.0 && rho < rho1 / std::numbers::e)
      e_fold = static_cast<double>(m) - 1.0 + (prev - rho1 / std::numbers::e) / std::max(prev - rho, 1e-12);
    prev = rho;
    tau += rho;
    if (static_cast<double>(m) >= 5.0 * tau && e_fold > 0.0) break;
  }
  out.window = static_cast<double>(std::min(m, max_lag));
  // The window's sum is short of the truth by about 12 tau / n of itself (mean and line removed,
  // the tail cut: measured on AR(1) windows of 30 to 500 correlation times, tests/logs).
  const double shrink = std::max(1.0 - 12.0 * std::max(tau, 0.5) / static_cast<double>(n), 0.5);
  out.integrated = std::max(tau, 0.5) / shrink;
  out.e_fold = e_fold / shrink;
  return out;
}

double autocorrelation_time(const std::vector<double>& x) { return correlation_times(x).integrated; }

double neighbour_block_correlation(double tau, double block) {
  if (!(tau > 0.0) || !(block > 0.0)) return 0.0;
  const double a = tau / block, e = 1.0 - std::exp(-block / tau);
  const double var = 2.0 * a * (1.0 - a * e);
  const double cov = a * a * e * e;
  return var > 0.0 ? std::clamp(cov / var, 0.0, 0.5) : 0.0;
}

CorrelatedMean correlated_mean(const std::vector<double>& t, const std::vector<double>& v, double start,
                               double end, bool detrend) {
  CorrelatedMean out;
  std::vector<double> x;
  for (std::size_t k = 0; k < t.size(); ++k)
    if (t[k] > start && t[k] <= end + 1e-9 && std::isfinite(v[k])) x.push_back(v[k]);
  out.n = static_cast<int>(x.size());
  if (out.n < 4 || t.size() < 2) return out;
  const double dt = t[1] - t[0];
  const Correlation cor = correlation_times(x);  // samples
  const double tau = cor.integrated;
  out.tau = tau * dt;
  out.n_eff = static_cast<double>(out.n) / (2.0 * tau);
  // The batches are long against the slower of the two times, so that a slow part under a
  // white floor still leaves them nearly independent.
  // (The 1/e point of a short series is itself noisy: it may lengthen the batches at most twofold.)
  const double slow = std::clamp(cor.e_fold, tau, 2.0 * tau);
  // And at least the window's kMaxBlocks-th: the autocorrelation time of a window only a few dozen
  // correlation times long is itself uncertain by a third (Sokal's variance of it), and batches cut
  // to an underestimate of it would be correlated, their scatter too small.
  const double block = std::max({kBlocksPerTau * slow * dt, 2.0 * dt, (end - start) / kMaxBlocks});
  out.block = block;
  // The project's batch means and window trend (dem/station/steady_state.h), on these blocks.
  const std::vector<double> ones(t.size(), 1.0);
  const dem::station::Estimate e = dem::station::block_mean(t, v, ones, start, end, block);
  const dem::station::WindowTrend tr = dem::station::window_trend(t, v, start, end, block);
  out.mean = e.value;
  out.blocks = tr.blocks;
  // The straight line through the samples themselves (least squares; equally spaced, so the
  // window's times are k dt): its slope, and the residuals' spread.
  double sxx = 0.0, sxy = 0.0, xm = 0.0;
  {
    const double n = static_cast<double>(x.size()), km = 0.5 * (n - 1.0);
    for (double y : x) xm += y;
    xm /= n;
    for (std::size_t k = 0; k < x.size(); ++k) {
      const double d = (static_cast<double>(k) - km) * dt;
      sxx += d * d;
      sxy += d * (x[k] - xm);
    }
    const double slope = sxy / sxx;
    double rss = 0.0;
    for (std::size_t k = 0; k < x.size(); ++k) {
      const double r = x[k] - xm - slope * (static_cast<double>(k) - km) * dt;
      rss += r * r;
    }
    out.sd = std::sqrt(rss / (n - 2.0));
    out.slope = slope;
  }
  out.rho1 = neighbour_block_correlation(slow, block / dt);
  const double widen = std::sqrt(1.0 + 2.0 * out.rho1);
  if (detrend && tr.blocks >= 3 && std::isfinite(tr.se_slope)) {
    // The line's value at the blocks' centre: se = sigma_resid / sqrt(b), and sigma_resid from
    // se_slope = sigma_resid / sqrt(sxx), sxx = L^2 b (b^2 - 1) / 12 for b blocks L apart.
    const double b = tr.blocks;
    out.se = std::max(tr.se_slope * block * std::sqrt((b * b - 1.0) / 12.0) * widen, out.sd / std::sqrt(out.n_eff));
    out.dof = b - 2.0;
  } else if (tr.blocks >= kMinBlocks && e.ok() && std::isfinite(e.se)) {
    // The larger of the batches' and the autocorrelation time's: two estimates of one number, each
    // too small in some windows; the larger is too small in far fewer (the bench's coverage).
    out.se = std::max(e.se * widen, out.sd / std::sqrt(out.n_eff));
    out.dof = static_cast<double>(out.blocks) - 1.0;
  } else {
    // Too short for batches (a tare of a few seconds): the autocorrelation time's standard error,
    // sd sqrt(2 tau / n), with as many degrees of freedom as independent samples less one.
    out.se = out.sd / std::sqrt(out.n_eff);
    out.dof = std::max(out.n_eff - 1.0, 1.0);
  }
  // The slope's standard error, the larger of the batches' line's and the samples' line's with
  // correlated residuals, sd sqrt(2 tau / sxx); its degrees of freedom those of the batches' line.
  // The line is judged on batches half as long as the mean's (twice as many degrees of freedom:
  // with four batches a t-quantile at 0.5 % is 9.9, with fourteen 3.4), their residuals' correlation
  // counted as an AR(1)'s, sqrt((1 + rho_1) / (1 - rho_1)).
  const double tblock = std::max({0.5 * kBlocksPerTau * slow * dt, 2.0 * dt, (end - start) / (2.0 * kMaxBlocks)});
  const dem::station::WindowTrend tt = dem::station::window_trend(t, v, start, end, tblock);
  const double r1 = neighbour_block_correlation(slow, tblock / dt);
  const double widen_line = std::sqrt((1.0 + r1) / (1.0 - r1));
  out.se_slope = std::max(std::isfinite(tt.se_slope) ? tt.se_slope * widen_line : 0.0, out.sd * std::sqrt(2.0 * tau / sxx));
  out.slope_dof = std::max(static_cast<double>(tt.blocks) - 2.0, 1.0);
  return out;
}

}  // namespace chutelab::logs
