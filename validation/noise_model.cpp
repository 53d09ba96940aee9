#include "validation/noise_model.h"

#include <algorithm>
#include <cmath>
#include <gsl/gsl_cdf.h>
#include <map>

#include "analytical/transfer_station.h"

namespace chutelab::validation {
namespace {

// Consistency factor of the median absolute deviation for a normal distribution.
constexpr double kMad = 1.4826;
// From this many readings a quantity's own median is its centre (a quantity the explanation misses as
// a whole is a discrepancy, not a set of outliers), and from kOwnScatter its own scatter counts.
constexpr int kOwnCentre = 3;
constexpr int kOwnScatter = 5;
// A discrepancy is fitted for a quantity of at least this many readings; fewer are left to the outlier test.
constexpr int kDiscrepancyPoints = 3;

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  if (v.size() % 2) return *mid;
  return 0.5 * (*mid + *std::max_element(v.begin(), mid));
}

}  // namespace

NoiseModel NoiseModel::stated(const Misfit& m) {
  NoiseModel nm;
  nm.discrepancy.assign(m.groups().size(), 0.0);
  nm.excluded.assign(m.size(), 0);
  return nm;
}

std::vector<double> NoiseModel::weights(const Misfit& m) const {
  std::vector<double> w(m.size());
  for (std::size_t i = 0; i < m.size(); ++i) {
    const auto& p = m.points()[i];
    const double tau = discrepancy.empty() ? 0.0 : discrepancy[p.group];
    w[i] = !excluded.empty() && excluded[i] ? 0.0 : 1.0 / std::sqrt(scale * scale + std::pow(tau / p.uncertainty, 2));
  }
  return w;
}

int NoiseModel::excluded_count() const { return static_cast<int>(std::count(excluded.begin(), excluded.end(), 1)); }

bool NoiseModel::settled_with(const NoiseModel& o) const {
  if (excluded != o.excluded || discrepancy.size() != o.discrepancy.size()) return false;
  for (std::size_t g = 0; g < discrepancy.size(); ++g)
    if ((discrepancy[g] > 0.0) != (o.discrepancy[g] > 0.0)) return false;
  return std::abs(scale - o.scale) <= 0.01 * o.scale;
}

std::vector<double> robust_deviation(const Misfit& m, const NoiseModel& nm, const std::vector<double>& r) {
  const auto w = nm.weights(m);
  // Each quantity's residuals about their own median (a quantity the explanation misses as a whole is
  // a discrepancy, not a set of outliers), in units of the larger of its own robust scatter and the
  // pooled one (a small quantity's scatter can come out small by chance), never below one.
  std::vector<double> centred(m.size(), 0.0), dev(m.size(), 0.0);
  std::vector<double> own(m.groups().size(), 0.0);
  std::vector<double> pooled;
  for (std::size_t g = 0; g < m.groups().size(); ++g) {
    std::vector<double> z;
    for (std::size_t i : m.groups()[g].points)
      if (w[i] > 0.0) z.push_back(r[i] * w[i]);
    const bool enough = static_cast<int>(z.size()) >= kOwnScatter;
    const double centre = static_cast<int>(z.size()) >= kOwnCentre ? median(z) : 0.0;
    std::vector<double> a;
    for (std::size_t i : m.groups()[g].points)
      if (w[i] > 0.0) {
        centred[i] = r[i] * w[i] - centre;
        a.push_back(std::abs(centred[i]));
        pooled.push_back(std::abs(centred[i]));
      }
    own[g] = enough ? kMad * median(a) : 0.0;
  }
  const double pool = std::max(1.0, kMad * median(pooled));
  for (std::size_t i = 0; i < m.size(); ++i)
    if (w[i] > 0.0) dev[i] = centred[i] / std::max(pool, own[m.points()[i].group]);
  return dev;
}

std::optional<std::size_t> find_outlier(const Misfit& m, const NoiseModel& nm, const std::vector<double>& r,
                                        double alpha, double max_share) {
  const auto w = nm.weights(m);
  const auto n = static_cast<int>(std::count_if(w.begin(), w.end(), [](double x) { return x > 0.0; }));
  if (n < kOwnScatter) return std::nullopt;
  if (nm.excluded_count() + 1 > std::max(1.0, max_share * (n + nm.excluded_count()))) return std::nullopt;
  const auto dev = robust_deviation(m, nm, r);
  // Any of n readings beyond this by chance: alpha.
  const double limit = gsl_cdf_ugaussian_Qinv(alpha / (2.0 * n));
  std::optional<std::size_t> worst;
  for (std::size_t i = 0; i < m.size(); ++i)
    if (w[i] > 0.0 && std::abs(dev[i]) > limit && (!worst || std::abs(dev[i]) > std::abs(dev[*worst]))) worst = i;
  return worst;
}

std::optional<std::size_t> find_readmitted(const Misfit& m, const NoiseModel& nm, const std::vector<double>& r,
                                           double alpha) {
  for (std::size_t i = 0; i < m.size(); ++i) {
    if (!nm.excluded[i]) continue;
    NoiseModel with = nm;
    with.excluded[i] = 0;
    // Judged without its quantity's model discrepancy: a variance widened for the whole quantity
    // reaches any reading, and a reading comes back only when a cause, not the widening, explains it.
    if (!with.discrepancy.empty()) with.discrepancy[m.points()[i].group] = 0.0;
    const auto w = with.weights(m);
    const auto n = static_cast<int>(std::count_if(w.begin(), w.end(), [](double x) { return x > 0.0; }));
    const double limit = gsl_cdf_ugaussian_Qinv(alpha / (2.0 * n));
    if (std::abs(robust_deviation(m, with, r)[i]) <= limit) return i;
  }
  return std::nullopt;
}

// tau with sum over the group of r^2 / (s^2 + tau^2 / u^2) = n: the group then scatters as its
// count says. The sum falls from its value at tau = 0 towards zero, so bisection finds it.
double discrepancy_for(const Misfit& m, const MisfitGroup& g, const std::vector<double>& r,
                       const std::vector<char>& excluded, double scale) {
  double n = 0.0, hi = 0.0;
  for (std::size_t i : g.points)
    if (!excluded[i]) {
      n += 1.0;
      hi = std::max(hi, std::abs(r[i]) * m.points()[i].uncertainty);
    }
  auto sum = [&](double tau) {
    double s = 0.0;
    for (std::size_t i : g.points)
      if (!excluded[i]) s += r[i] * r[i] / (scale * scale + std::pow(tau / m.points()[i].uncertainty, 2));
    return s;
  };
  if (sum(0.0) <= n) return 0.0;
  double lo = 0.0;
  hi = std::max(hi * std::sqrt(n), 1e-300);
  for (int it = 0; it < 200 && hi - lo > 1e-12 * hi; ++it) {
    const double mid = 0.5 * (lo + hi);
    (sum(mid) > n ? lo : hi) = mid;
  }
  return hi;
}

NoiseModel assess_noise(const Misfit& m, const NoiseModel& nm, const std::vector<double>& r, int k, double alpha,
                        ScaleEstimate* out) {
  NoiseModel next = NoiseModel::stated(m);
  next.excluded = nm.excluded;
  const auto& groups = m.groups();
  const std::size_t G = groups.size();
  std::vector<double> chi2(G, 0.0);
  std::vector<int> count(G, 0);
  for (std::size_t g = 0; g < G; ++g)
    for (std::size_t i : groups[g].points)
      if (!next.excluded[i]) {
        chi2[g] += r[i] * r[i];
        ++count[g];
      }
  int eligible = 0;
  for (std::size_t g = 0; g < G; ++g) eligible += count[g] >= kDiscrepancyPoints ? 1 : 0;
  // A quantity is discrepant when it scatters more than the others do (their pooled ratio, at least
  // the stated one), beyond chance at alpha over the quantities that could have been picked; one at
  // a time, the most significant first, and never all of them (that is a common scale).
  // A quantity that had a discrepancy keeps it while it still scatters more than its count says.
  std::vector<char> flagged(G, 0);
  for (std::size_t g = 0; g < G && g < nm.discrepancy.size(); ++g)
    if (nm.discrepancy[g] > 0.0 && chi2[g] > count[g]) flagged[g] = 1;
  for (int picked = static_cast<int>(std::count(flagged.begin(), flagged.end(), 1)); picked + 1 < eligible; ++picked) {
    double total = 0.0;
    int total_n = 0;
    for (std::size_t g = 0; g < G; ++g)
      if (!flagged[g]) total += chi2[g], total_n += count[g];
    std::optional<std::size_t> worst;
    double worst_p = 1.0;
    for (std::size_t g = 0; g < G; ++g) {
      if (flagged[g] || count[g] < kDiscrepancyPoints) continue;
      // Against the stated uncertainties while the rest scatter as stated; against the rest's own
      // scatter (an F test, the scale being estimated) where they scatter more.
      const int rest_n = total_n - count[g];
      const double ratio = rest_n > 0 ? (total - chi2[g]) / rest_n : 1.0;
      const double p = ratio > 1.0 ? gsl_cdf_fdist_Q((chi2[g] / count[g]) / ratio, count[g], rest_n)
                                   : gsl_cdf_chisq_Q(chi2[g], count[g]);
      if (p < worst_p) worst_p = p, worst = g;
    }
    // Half the family's alpha: the other half judges what an explanation leaves (validation/diagnosis_findings.cpp, leftovers_of).
    if (!worst || worst_p >= 0.5 * alpha / eligible) break;
    flagged[*worst] = 1;
  }
  // The common scale from the rest.
  double rest = 0.0;
  int rest_n = 0;
  for (std::size_t g = 0; g < G; ++g)
    if (!flagged[g]) rest += chi2[g], rest_n += count[g];
  ScaleEstimate s;
  s.dof = std::max(1, rest_n - k);
  s.factor = std::sqrt(rest / s.dof);
  s.p_high = gsl_cdf_chisq_Q(rest, s.dof);
  s.p_low = gsl_cdf_chisq_P(rest, s.dof);
  next.scale = s.p_high < alpha ? std::max(1.0, s.factor) : 1.0;
  for (std::size_t g = 0; g < G; ++g)
    if (flagged[g]) next.discrepancy[g] = discrepancy_for(m, groups[g], r, next.excluded, next.scale);
  if (out) *out = s;
  return next;
}

Drivers drivers_of(const Misfit& m) {
  const Dataset& d = m.dataset();
  Drivers out;
  out.names = {"belt speed", "mass flow", "drop height", "distance along the flight"};
  out.value.assign(out.names.size(), std::vector<double>(m.size(), 0.0));
  std::vector<double> drop(d.stations.size(), 0.0);
  for (std::size_t c = 0; c < d.stations.size(); ++c) try {
      drop[c] = analytical::analyse_transfer(d.stations[c]).drop_height();
    } catch (const std::exception&) {
      drop[c] = 0.0;
    }
  for (std::size_t i = 0; i < m.size(); ++i) {
    const auto& p = m.points()[i];
    const Station& st = d.stations[p.condition];
    out.value[0][i] = st.belt_speed;
    out.value[1][i] = st.mass_flow;
    out.value[2][i] = drop[p.condition];
    out.value[3][i] = p.q ? 0.0 : m.source().queries(p.condition)[p.query].x;
  }
  return out;
}

namespace {

// The two-sided p of a straight line's slope through (x, z), its residual variance never below
// `floor` (the noise model's variance of one z); 1 when x does not vary.
double slope_p(const std::vector<double>& x, const std::vector<double>& z, double floor) {
  const auto n = static_cast<double>(x.size());
  if (n < 4) return 1.0;
  double mx = 0, mz = 0;
  for (std::size_t i = 0; i < x.size(); ++i) mx += x[i], mz += z[i];
  mx /= n, mz /= n;
  double sxz = 0, sxx = 0, szz = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double dx = x[i] - mx, dz = z[i] - mz;
    sxz += dx * dz, sxx += dx * dx, szz += dz * dz;
  }
  if (!(sxx > 1e-24 * (mx * mx + 1e-300))) return 1.0;
  const double slope = sxz / sxx;
  const double var = std::max(floor, (szz - slope * sxz) / (n - 2));
  return std::min(1.0, 2.0 * gsl_cdf_tdist_Q(std::abs(slope) / std::sqrt(var / sxx), n - 2));
}

}  // namespace

std::vector<GroupScatter> group_scatter(const Misfit& m, const NoiseModel& nm, const std::vector<double>& r,
                                        const Drivers& drivers) {
  const auto w = nm.weights(m);
  std::vector<GroupScatter> out;
  for (std::size_t g = 0; g < m.groups().size(); ++g) {
    GroupScatter s;
    s.group = g;
    // Per condition: the mean weighted residual. The points of one condition (a stream limit at
    // several x) come from one run and one picture, so their errors go together: bias and trends
    // with the operating variables count conditions, not points.
    std::map<std::size_t, std::pair<double, int>> by_condition;
    std::vector<double> z, along;
    for (std::size_t i : m.groups()[g].points) {
      if (w[i] <= 0.0) continue;
      const double zi = r[i] * w[i];
      s.chi2 += zi * zi;
      z.push_back(zi);
      along.push_back(drivers.value.back()[i]);
      auto& c = by_condition[m.points()[i].condition];
      c.first += zi, ++c.second;
    }
    s.n = static_cast<int>(z.size());
    if (s.n == 0) {
      out.push_back(s);
      continue;
    }
    for (double x : z) s.mean += x / s.n;
    s.p_excess = gsl_cdf_chisq_Q(s.chi2, s.n);
    std::vector<double> cz;
    for (const auto& [c, sum] : by_condition) cz.push_back(sum.first / sum.second);
    // Bias and trend are judged against the larger of the conditions' own scatter and the one the
    // noise model gives one reading (1 in weighted residuals): uncertainties stated generously do
    // not turn a bias far inside them into a finding.
    const auto nc = static_cast<double>(cz.size());
    if (nc >= 3) {
      double mc = 0, ss = 0;
      for (double x : cz) mc += x / nc;
      for (double x : cz) ss += (x - mc) * (x - mc);
      const double var = std::max(1.0, ss / (nc - 1));
      s.p_bias = std::min(1.0, 2.0 * gsl_cdf_tdist_Q(std::abs(mc) / std::sqrt(var / nc), nc - 1));
    }
    // Operating variables per condition (in the map's order), the distance along the flight per point.
    for (std::size_t k = 0; k + 1 < drivers.names.size(); ++k) {
      std::map<std::size_t, double> value;
      for (std::size_t i : m.groups()[g].points)
        if (w[i] > 0.0) value[m.points()[i].condition] = drivers.value[k][i];
      std::vector<double> x;
      for (const auto& [c, v] : value) x.push_back(v);
      if (const double p = slope_p(x, cz, 1.0); p < s.p_trend) s.p_trend = p, s.trend_driver = drivers.names[k];
    }
    if (const double p = slope_p(along, z, 1.0); p < s.p_trend) s.p_trend = p, s.trend_driver = drivers.names.back();
    out.push_back(s);
  }
  return out;
}

}  // namespace chutelab::validation
