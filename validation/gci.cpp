#include "validation/gci.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <stdexcept>
#include <vector>

namespace chutelab::validation {

std::string_view name(GciCase c) {
  switch (c) {
    case GciCase::three_level: return "three-level";
    case GciCase::order_bounded: return "order-bounded";
    case GciCase::two_level: return "two-level";
    case GciCase::noise_dominated: return "noise-dominated";
    case GciCase::oscillatory: return "oscillatory";
    case GciCase::diverging: return "diverging";
  }
  return "";
}

namespace {

constexpr double kFsThree = 1.25;  // Roache, three or more levels with a confirmed order
constexpr double kFsBound = 3.0;   // Roache, two levels or an unconfirmed order

// Celik et al. (2008) Eq. 3 for monotone differences (s = +1), by fixed-point iteration on the
// signed form, so that differences growing with refinement give p <= 0 instead of being hidden
// by the absolute value. nullopt when the iteration does not settle.
std::optional<double> observed_order(double r21, double r32, double e21, double e32) {
  const double lr = std::log(e32 / e21);
  double p = lr / std::log(r21);  // exact for a constant ratio (q = 0)
  if (std::abs(r21 - r32) < 1e-12 * r21) return p;
  // With unequal ratios e32 < e21 does not mean divergence (a small r32 gives a small e32), so the
  // constant-ratio value only starts the iteration when it is positive.
  if (!(p > 0.0)) p = 1.0;
  for (int it = 0; it < 500; ++it) {
    if (p <= 0.0) return p;  // diverging: q(p) has no meaning there
    const double q = std::log((std::pow(r21, p) - 1.0) / (std::pow(r32, p) - 1.0));
    const double next = (lr + q) / std::log(r21);
    if (!std::isfinite(next)) return std::nullopt;
    if (std::abs(next - p) < 1e-12 * std::max(1.0, std::abs(p))) return next;
    // Under-relaxed: the plain iteration can cycle for ratios far from each other.
    p = 0.5 * (p + next);
  }
  return std::nullopt;
}

}  // namespace

GciEstimate gci_estimate(std::span<const LadderLevel> in, const GciOptions& o) {
  if (in.size() < 2) throw std::invalid_argument("a GCI needs at least two levels");
  std::vector<LadderLevel> lv(in.begin(), in.end());
  for (const auto& l : lv) {
    if (!(l.h > 0.0) || !std::isfinite(l.h))
      throw std::invalid_argument(fmt::format("refinement parameter must be positive, got {}", l.h));
    if (!std::isfinite(l.value)) throw std::invalid_argument("a level's value is not finite");
    if (!(l.standard_error >= 0.0) || !std::isfinite(l.standard_error))
      throw std::invalid_argument("a level's standard error must be a finite number >= 0");
  }
  std::sort(lv.begin(), lv.end(), [](const auto& a, const auto& b) { return a.h < b.h; });
  for (std::size_t i = 1; i < lv.size(); ++i)
    if (lv[i].h <= lv[i - 1].h * (1.0 + 1e-12))
      throw std::invalid_argument(fmt::format("two levels share h = {}", lv[i].h));
  if (lv.size() > 3) lv.resize(3);

  const auto& l1 = lv[0];
  const auto& l2 = lv[1];
  const double r21 = l2.h / l1.h;
  const double e21 = l2.value - l1.value;
  const double se21 = std::hypot(l1.standard_error, l2.standard_error);
  const bool res21 = std::abs(e21) > o.resolution_k * se21;

  GciEstimate g;
  g.fine_value = l1.value;
  auto finish = [&] {
    if (l1.value != 0.0) g.gci_fine_relative = g.gci_fine / std::abs(l1.value);
    g.u_disc = g.gci_fine / o.coverage_k;
  };
  // The Fs = 3 two-level band of the finest pair with the assumed order, on the difference seen
  // or the largest one the noise could hide.
  auto bound = [&](GciCase kind, std::string why) {
    g.kind = kind;
    g.order = o.assumed_order;
    g.safety_factor = kFsBound;
    const double d = std::max(std::abs(e21), o.resolution_k * se21);
    g.gci_fine = kFsBound * d / (std::pow(r21, g.order) - 1.0);
    g.method = fmt::format("{}; two-level GCI bound of the finest pair, p = {:g} assumed, Fs = 3", why,
                           g.order);
  };

  // A difference the noise hides: the error estimate e / (r^p - 1) of the widest pair and its own
  // standard error, in quadrature, is already a standard uncertainty (no Fs, no coverage factor).
  auto statistical = [&](const LadderLevel& a, const LadderLevel& b, std::string why) {
    g.kind = GciCase::noise_dominated;
    g.order = o.assumed_order;
    g.safety_factor = 1.0;
    const double r = b.h / a.h, e = b.value - a.value, se = std::hypot(a.standard_error, b.standard_error);
    g.u_disc = std::hypot(e, se) / (std::pow(r, g.order) - 1.0);
    g.gci_fine = o.coverage_k * g.u_disc;
    g.method = fmt::format("{}; u = sqrt(e^2 + se^2) / (r^p - 1) of the widest pair (e = {:.3g}, se = {:.3g}, "
                           "r = {:.3g}), p = {:g} assumed",
                           why, std::abs(e), se, r, g.order);
  };

  if (lv.size() == 2) {
    if (!res21) {
      statistical(l1, l2, "two levels, difference not resolved against its standard error");
      finish();
      return g;
    }
    bound(GciCase::two_level, "two levels");
    const double rp = std::pow(r21, g.order);
    g.extrapolated = (rp * l1.value - l2.value) / (rp - 1.0);
    finish();
    return g;
  }

  const auto& l3 = lv[2];
  const double r32 = l3.h / l2.h;
  const double e32 = l3.value - l2.value;
  const double se32 = std::hypot(l2.standard_error, l3.standard_error);
  const bool res32 = std::abs(e32) > o.resolution_k * se32;

  if (!res21 || !res32) {
    statistical(l1, l3,
                fmt::format("three levels, {} not resolved against the statistical error (|e| <= {:g} se)",
                            !res21 && !res32 ? "both differences" : !res21 ? "the fine difference" : "the coarse difference",
                            o.resolution_k));
    finish();
    return g;
  }
  if ((e21 > 0.0) != (e32 > 0.0)) {
    bound(GciCase::oscillatory, "three levels, oscillatory (differences of opposite sign)");
    const double hi = std::max({l1.value, l2.value, l3.value});
    const double lo = std::min({l1.value, l2.value, l3.value});
    if (kFsBound * 0.5 * (hi - lo) > g.gci_fine) {
      g.gci_fine = kFsBound * 0.5 * (hi - lo);
      g.method = "three levels, oscillatory (differences of opposite sign); Fs = 3 times half the "
                 "range of the three values";
    }
    finish();
    return g;
  }
  const auto p = observed_order(r21, r32, e21, e32);
  g.observed_order = p;
  if (!p || *p <= 0.0) {
    bound(GciCase::diverging, p ? fmt::format("three levels, differences grow with refinement (p = {:.2f})", *p)
                                : std::string("three levels, the observed order did not converge"));
    finish();
    return g;
  }
  g.order = std::clamp(*p, o.min_order, o.max_order);
  const bool inside = g.order == *p;
  g.kind = inside ? GciCase::three_level : GciCase::order_bounded;
  g.safety_factor = inside ? kFsThree : kFsBound;
  const double rp = std::pow(r21, g.order);
  g.extrapolated = (rp * l1.value - l2.value) / (rp - 1.0);
  g.gci_fine = g.safety_factor * std::abs(e21) / (rp - 1.0);
  g.method = inside ? fmt::format("three-level GCI (Celik et al. 2008), observed p = {:.2f}, Fs = 1.25", *p)
                    : fmt::format("three-level GCI, observed p = {:.2f} outside [{:g}, {:g}], used p = {:g}, Fs = 3",
                                  *p, o.min_order, o.max_order, g.order);
  finish();
  return g;
}

LadderUncertainty ladder_uncertainty(std::span<const LadderRun> runs, const GciOptions& o) {
  LadderUncertainty out;
  std::size_t queries = 0;
  for (const auto& r : runs)
    if (r.prediction) queries = std::max(queries, r.prediction->trajectory.size());
  auto estimate = [&](auto value_of, auto se_of) -> std::optional<GciEstimate> {
    std::vector<LadderLevel> levels;
    for (const auto& r : runs) {
      if (!r.prediction) continue;
      if (const std::optional<double> v = value_of(*r.prediction))
        levels.push_back({r.h, *v, se_of(*r.prediction).value_or(0.0)});
    }
    if (levels.size() < 2) return std::nullopt;
    return gci_estimate(levels, o);
  };
  auto nth = [](const std::vector<std::optional<double>>& v, std::size_t t) {
    return t < v.size() ? v[t] : std::nullopt;
  };
  for (Quantity q : kAllQuantities) {
    auto& e = out.estimate[static_cast<std::size_t>(q)];
    e = estimate([q](const ModelPrediction& p) { return p.values[q]; },
                 [q](const ModelPrediction& p) { return p.uncertainty[q]; });
    if (e) {
      out.u_disc[q] = e->u_disc;
      out.methods[static_cast<std::size_t>(q)].push_back(e->method);
    }
  }
  out.trajectory.resize(queries);
  out.trajectory_estimate.resize(queries);
  for (std::size_t t = 0; t < queries; ++t) {
    out.trajectory_estimate[t] = estimate([&](const ModelPrediction& p) { return nth(p.trajectory, t); },
                                          [&](const ModelPrediction& p) { return nth(p.trajectory_uncertainty, t); });
    if (out.trajectory_estimate[t]) out.trajectory[t] = out.trajectory_estimate[t]->u_disc;
  }
  return out;
}

LadderUncertainty combine_ladders(std::span<const LadderUncertainty> parts) {
  LadderUncertainty out;
  if (parts.empty()) return out;
  auto rss = [](std::optional<double>& acc, const std::optional<double>& v) {
    if (v) acc = acc ? std::hypot(*acc, *v) : *v;
  };
  std::size_t queries = 0;
  for (const auto& p : parts) queries = std::max(queries, p.trajectory.size());
  out.trajectory.resize(queries);
  out.trajectory_estimate.resize(queries);
  for (const auto& p : parts) {
    for (Quantity q : kAllQuantities) {
      const auto k = static_cast<std::size_t>(q);
      std::optional<double> acc = out.u_disc[q];
      rss(acc, p.u_disc[q]);
      if (acc) out.u_disc[q] = *acc;
      if (!out.estimate[k]) out.estimate[k] = p.estimate[k];
      out.methods[k].insert(out.methods[k].end(), p.methods[k].begin(), p.methods[k].end());
    }
    for (std::size_t t = 0; t < p.trajectory.size(); ++t) {
      rss(out.trajectory[t], p.trajectory[t]);
      if (!out.trajectory_estimate[t] && t < p.trajectory_estimate.size()) out.trajectory_estimate[t] = p.trajectory_estimate[t];
    }
  }
  return out;
}

void apply_discretisation(ModelPrediction& fine, const LadderUncertainty& u) {
  fine.discretisation = u.u_disc;
  fine.trajectory_discretisation = u.trajectory;
  for (Quantity q : kAllQuantities) {
    const auto& m = u.methods[static_cast<std::size_t>(q)];
    if (!m.empty()) fine.notes.push_back(fmt::format("u_num,disc of {}: {}", info(q).symbol, fmt::join(m, "; plus ")));
  }
}

}  // namespace chutelab::validation
