#include "dem/station/steady_state.h"

#include <algorithm>
#include <cmath>

namespace chutelab::dem::station {
namespace {

struct Blocks {
  std::vector<double> mean, weight;
  std::vector<double> start;  // block start times
};

// Blocks of length `block` counted back from `end`, covering (start, end]; partial blocks dropped.
Blocks make_blocks(const std::vector<double>& t, const std::vector<double>& v, const std::vector<double>* w,
                   double start, double end, double block) {
  Blocks b;
  const int n = static_cast<int>(std::floor((end - start) / block + 1e-9));
  if (n <= 0) return b;
  std::vector<double> sum(static_cast<std::size_t>(n), 0.0), wsum(static_cast<std::size_t>(n), 0.0);
  const double tol = 1e-9 * block;
  for (std::size_t k = 0; k < t.size(); ++k) {
    if (t[k] <= end - n * block + tol || t[k] > end + tol) continue;
    int i = static_cast<int>(std::floor((t[k] - (end - n * block) - tol) / block));
    i = std::clamp(i, 0, n - 1);
    const double wk = w ? (*w)[k] : 1.0;
    if (!(wk > 0.0) || !std::isfinite(v[k])) continue;
    sum[static_cast<std::size_t>(i)] += wk * v[k];
    wsum[static_cast<std::size_t>(i)] += wk;
  }
  for (int i = 0; i < n; ++i) {
    if (!(wsum[static_cast<std::size_t>(i)] > 0.0)) continue;
    b.mean.push_back(sum[static_cast<std::size_t>(i)] / wsum[static_cast<std::size_t>(i)]);
    b.weight.push_back(wsum[static_cast<std::size_t>(i)]);
    b.start.push_back(end - (n - i) * block);
  }
  return b;
}

double sd(const std::vector<double>& x) {
  if (x.size() < 2) return 0.0;
  double m = 0.0;
  for (double v : x) m += v;
  m /= static_cast<double>(x.size());
  double s = 0.0;
  for (double v : x) s += (v - m) * (v - m);
  return std::sqrt(s / static_cast<double>(x.size() - 1));
}

// The ratios of two series' block means (e.g. an impact point, moment / force), block by block: the
// blocks both series have (a block with no finite sample is dropped from its series), a zero
// denominator left out.
Blocks ratio_blocks(const std::vector<double>& t, const std::vector<double>& num, const std::vector<double>& den,
                    double start, double end, double block) {
  const Blocks bn = make_blocks(t, num, nullptr, start, end, block), bd = make_blocks(t, den, nullptr, start, end, block);
  Blocks r;
  if (bn.mean.size() != bd.mean.size()) return r;
  for (std::size_t i = 0; i < bn.mean.size(); ++i) {
    if (bn.start[i] != bd.start[i] || bd.mean[i] == 0.0) continue;
    r.mean.push_back(bn.mean[i] / bd.mean[i]);
    r.weight.push_back(1.0);
    r.start.push_back(bn.start[i]);
  }
  return r;
}

}  // namespace

SteadyWindow detect_steady(const std::vector<double>& t, const std::vector<double>& v, const SteadyParams& p) {
  SteadyWindow wdw;
  if (t.size() < 2) return wdw;
  const double dt = t[1] - t[0];
  const double t0 = t.front() - dt, end = t.back();
  const Blocks all = make_blocks(t, v, nullptr, t0, end, p.detect_block);
  if (all.mean.size() < 2) return wdw;
  const double tail_start = std::max(t0, end - p.detect_tail);
  const Blocks tail = make_blocks(t, v, nullptr, tail_start, end, p.detect_block);
  if (tail.mean.empty()) return wdw;
  double ref = 0.0;
  for (double m : tail.mean) ref += m;
  ref /= static_cast<double>(tail.mean.size());
  const double tol = std::max(p.relative_tolerance * std::abs(ref), p.sd_tolerance * sd(tail.mean));
  // First block from which on every block stays within tol of the reference.
  std::size_t first = all.mean.size();
  for (std::size_t i = all.mean.size(); i-- > 0;) {
    if (std::abs(all.mean[i] - ref) > tol) break;
    first = i;
  }
  if (first >= all.mean.size() || !(std::abs(ref) > 0.0)) {
    wdw.end = end;
    return wdw;
  }
  const double start = all.start[first] + p.detect_block;
  const int n = static_cast<int>(std::floor((end - start) / p.mean_block + 1e-9));
  wdw.end = end;
  if (n < 1) return wdw;
  wdw.found = true;
  wdw.blocks = n;
  wdw.start = end - n * p.mean_block;
  return wdw;
}

Estimate block_mean(const std::vector<double>& t, const std::vector<double>& v, const std::vector<double>& w,
                    double start, double end, double block) {
  Estimate e;
  double sum = 0.0, wsum = 0.0;
  for (std::size_t k = 0; k < t.size(); ++k) {
    if (t[k] <= start || t[k] > end + 1e-12 || !std::isfinite(v[k]) || !(w[k] > 0.0)) continue;
    sum += w[k] * v[k];
    wsum += w[k];
    ++e.n;
  }
  if (!(wsum > 0.0)) return e;
  e.value = sum / wsum;
  const Blocks b = make_blocks(t, v, &w, start, end, block);
  if (b.mean.size() >= 2) e.se = sd(b.mean) / std::sqrt(static_cast<double>(b.mean.size()));
  return e;
}

Estimate block_ratio(const std::vector<double>& t, const std::vector<double>& num, const std::vector<double>& den,
                     double start, double end, double block) {
  Estimate e;
  const std::vector<double> ones(t.size(), 1.0);
  const Estimate a = block_mean(t, num, ones, start, end, block), b = block_mean(t, den, ones, start, end, block);
  if (!a.ok() || !b.ok() || b.value == 0.0) return e;
  e.value = a.value / b.value;
  e.n = a.n;
  const Blocks r = ratio_blocks(t, num, den, start, end, block);
  if (r.mean.size() >= 2) e.se = sd(r.mean) / std::sqrt(static_cast<double>(r.mean.size()));
  return e;
}

namespace {

WindowTrend trend_of(const Blocks& b, double start, double end) {
  WindowTrend out;
  const std::size_t n = b.mean.size();
  out.span = end - start;
  out.blocks = static_cast<int>(n);
  if (n < 3) return out;  // too few blocks to see a trend; the window length rule decides
  double tm = 0.0, vm = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    tm += b.start[i];
    vm += b.mean[i];
  }
  tm /= static_cast<double>(n);
  vm /= static_cast<double>(n);
  double sxx = 0.0, sxy = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    sxx += (b.start[i] - tm) * (b.start[i] - tm);
    sxy += (b.start[i] - tm) * (b.mean[i] - vm);
  }
  const double slope = sxy / sxx;
  double rss = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const double r = b.mean[i] - vm - slope * (b.start[i] - tm);
    rss += r * r;
  }
  out.slope = slope;
  out.se_slope = std::sqrt(rss / static_cast<double>(n - 2) / sxx);
  out.mean = vm;
  return out;
}

}  // namespace

WindowTrend window_trend(const std::vector<double>& t, const std::vector<double>& v, double start, double end,
                         double block) {
  return trend_of(make_blocks(t, v, nullptr, start, end, block), start, end);
}

WindowTrend window_trend_ratio(const std::vector<double>& t, const std::vector<double>& num,
                               const std::vector<double>& den, double start, double end, double block) {
  return trend_of(ratio_blocks(t, num, den, start, end, block), start, end);
}

bool drifting(const std::vector<double>& t, const std::vector<double>& v, double start, double end, double block,
              double rel) {
  return window_trend(t, v, start, end, block).drifting(rel);
}

}  // namespace chutelab::dem::station
