#include "logs/steady_log.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>

namespace chutelab::logs {
namespace {

using dem::station::detect_steady;
using dem::station::SteadyWindow;

// The samples of (a, b], read forwards or backwards in time (backwards: time measured back from b,
// so that detect_steady's tail is the part nearest a).
struct Part {
  std::vector<double> t, v;
};
Part part(const std::vector<double>& t, const std::vector<double>& v, double a, double b, bool backwards) {
  Part p;
  for (std::size_t k = 0; k < t.size(); ++k)
    if (t[k] > a && t[k] <= b) {
      p.t.push_back(t[k]);
      p.v.push_back(v[k]);
    }
  if (backwards) {
    // Time measured back from b, one step per sample, so that detect_steady's tail is nearest a.
    std::reverse(p.v.begin(), p.v.end());
    const double dt = p.t.size() > 1 ? p.t[1] - p.t[0] : 0.0;
    for (std::size_t k = 0; k < p.t.size(); ++k) p.t[k] = static_cast<double>(k + 1) * dt;
  }
  return p;
}

// The steady stretch of part (a, b]: forwards, the window found is (start, b]; backwards, (a, b - start'].
Span steady_in(const std::vector<double>& t, const std::vector<double>& v, double a, double b, bool backwards,
               double dt, bool& found) {
  found = false;
  const Part p = part(t, v, a, b, backwards);
  if (p.t.size() < 6) return {};
  const double len = p.t.back() - p.t.front() + dt;
  const SteadyWindow w = detect_steady(p.t, p.v, log_steady_params(dt, 0.75 * len));
  if (!w.found) return {};
  found = true;
  const double from_start = w.start - (p.t.front() - dt);  // how far into the part the steady stretch starts
  return backwards ? Span{a, b - from_start} : Span{a + from_start, b};
}

double percentile(std::vector<double> x, double q) {
  if (x.empty()) return 0.0;
  const std::size_t k = std::min(x.size() - 1, static_cast<std::size_t>(q * static_cast<double>(x.size() - 1)));
  std::nth_element(x.begin(), x.begin() + static_cast<std::ptrdiff_t>(k), x.end());
  return x[k];
}

}  // namespace

dem::station::SteadyParams log_steady_params(double dt, double tail) {
  dem::station::SteadyParams p;
  p.detect_block = std::max(1.0, 3.0 * dt);
  p.mean_block = p.detect_block;
  p.detect_tail = std::max(tail, 2.0 * p.detect_block);
  p.relative_tolerance = 0.005;
  p.sd_tolerance = 3.0;
  return p;
}

LogSegments find_segments(const std::vector<double>& t, const std::vector<double>& load) {
  LogSegments s;
  const std::size_t n = t.size();
  if (n < 8) {
    s.warnings.push_back(fmt::format("only {} samples: no steady window can be found", n));
    return s;
  }
  const double dt = t[1] - t[0];
  const double t0 = t.front() - dt, t1 = t.back();
  // Smoothed over 0.2 s (at least 3 samples), centred, so that noise does not cross the threshold.
  const int half = std::max(1, static_cast<int>(std::lround(0.1 / dt)));
  std::vector<double> sm(n);
  {
    std::vector<double> c(n + 1, 0.0);
    for (std::size_t k = 0; k < n; ++k) c[k + 1] = c[k] + load[k];
    for (std::size_t k = 0; k < n; ++k) {
      const std::size_t a = k >= static_cast<std::size_t>(half) ? k - half : 0;
      const std::size_t b = std::min(n, k + half + 1);
      sm[k] = (c[b] - c[a]) / static_cast<double>(b - a);
    }
  }
  const double level = percentile(sm, 0.95);
  if (!(level > 0.0)) {
    s.warnings.push_back("the plate never carries a load: no loaded part in the log");
    return s;
  }
  const double thr = 0.5 * level;
  std::size_t on = n, off = n;
  for (std::size_t k = 0; k < n; ++k)
    if (sm[k] > thr) {
      if (on == n) on = k;
      off = k;
    }
  s.loaded = true;
  s.load_on = t[on];
  s.load_off = t[off];
  // Where the load leaves its zero: the last time before the crossing within 5 % of its level.
  std::size_t st = on;
  while (st > 0 && sm[st - 1] > 0.05 * level) --st;
  s.load_start = st > 0 ? t[st - 1] : t.front();
  const double mid = 0.5 * (s.load_on + s.load_off);
  bool f1 = false, f2 = false;
  const Span a = steady_in(t, load, s.load_on - dt, mid, false, dt, f1);
  const Span b = steady_in(t, load, mid, s.load_off, true, dt, f2);
  s.steady = f1 && f2 && a.ok() && b.ok();
  if (s.steady) {
    // A transient that settles exponentially is still up to its tolerance (three block scatters)
    // off where the rule accepts it, and its tail would bias the mean by a fraction of the mean's
    // uncertainty; as long again after it, that fraction is squared. So the window starts twice as
    // far from the load's change as the rule says, and ends likewise. (A gust the rule took for the
    // transient's end costs the window that much more: the added stretch is at most a quarter of
    // the loaded part.)
    const double cap = 0.25 * (s.load_off - s.load_on);
    s.window = {a.start + std::min(a.start - s.load_on, cap), b.end - std::min(s.load_off - b.end, cap)};
    if (!s.window.ok()) {
      s.steady = false;
      s.warnings.push_back("the start-up and shut-down transients leave no steady window between them");
    }
  }
  if (!s.steady) {
    const double q = 0.25 * (s.load_off - s.load_on);
    s.window = {s.load_on + q, s.load_off - q};
    s.warnings.push_back(fmt::format(
        "no steady load found between {:.2f} s and {:.2f} s (not stationary): the middle half, {:.2f}-{:.2f} s, "
        "is averaged instead",
        s.load_on, s.load_off, s.window.start, s.window.end));
  }
  // The zero: the unloaded parts at least 0.5 s long, read away from the load's change.
  constexpr double kMinTare = 0.5;
  if (s.load_on - t0 >= kMinTare) {
    bool f = false;
    const Span z = steady_in(t, load, t0, s.load_on - dt, true, dt, f);
    s.before = f ? z : Span{t0, s.load_on - dt - std::min(1.0, 0.5 * (s.load_on - t0))};
  }
  if (t1 - s.load_off >= kMinTare) {
    bool f = false;
    const Span z = steady_in(t, load, s.load_off + dt, t1, false, dt, f);
    s.after = f ? z : Span{s.load_off + dt + std::min(1.0, 0.5 * (t1 - s.load_off)), t1};
  }
  if (!s.before.ok() && !s.after.ok())
    s.warnings.push_back("no unloaded part before or after the load: the zero is the layout's, not checked");
  return s;
}

}  // namespace chutelab::logs
