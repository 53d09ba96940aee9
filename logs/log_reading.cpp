#include "logs/log_reading.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <functional>

namespace chutelab::logs {

bool ConditionReading::drift_flagged() const {
  return std::any_of(zeros.begin(), zeros.end(), [](const ChannelZero& z) { return z.drift_flag; });
}
bool ConditionReading::creep_flagged() const {
  return std::any_of(quantities.begin(), quantities.end(), [](const QuantityReading& q) { return q.creep; });
}
const QuantityReading* ConditionReading::find(Quantity q) const {
  for (const auto& r : quantities)
    if (r.quantity == q) return &r;
  return nullptr;
}

namespace {

bool plate(Role r) { return r == Role::normal || r == Role::shear; }

// The plate's quantities from its channels' values (output unit N; heights in m).
struct PlateQuantities {
  std::vector<Quantity> names;
  std::function<std::vector<double>(const std::vector<double>&)> f;
};

PlateQuantities plate_quantities(const Layout& l, const std::vector<std::size_t>& idx) {
  PlateQuantities p;
  const bool n = l.has(Role::normal), s = l.has(Role::shear), y = l.gives_impact_point();
  if (n) p.names.push_back(Quantity::normal_force);
  if (s) p.names.push_back(Quantity::shear_force);
  if (n && s) p.names.push_back(Quantity::resultant_force);
  if (y) p.names.push_back(Quantity::impact_point_y);
  p.f = [&l, idx, n, s, y](const std::vector<double>& m) {
    double rn = 0.0, rs = 0.0, moment = 0.0;
    for (std::size_t j = 0; j < idx.size(); ++j) {
      const Channel& c = l.channels[idx[j]];
      if (c.role == Role::normal) {
        rn += m[j];
        if (c.y) moment += m[j] * *c.y;
      } else {
        rs += m[j];
      }
    }
    std::vector<double> out;
    if (n) out.push_back(rn);
    if (s) out.push_back(rs);
    if (n && s) out.push_back(std::hypot(rn, rs));
    if (y) out.push_back(rn != 0.0 ? moment / rn : 0.0);
    return out;
  };
  return p;
}

std::vector<double> slice(const std::vector<double>& t, const std::vector<double>& v, const Span& s) {
  std::vector<double> out;
  for (std::size_t k = 0; k < t.size(); ++k)
    if (t[k] > s.start && t[k] <= s.end + 1e-9) out.push_back(v[k]);
  return out;
}

double mean_in(const std::vector<double>& t, const std::vector<double>& v, const Span& s) {
  const auto x = slice(t, v, s);
  double m = 0.0;
  for (double a : x) m += a;
  return x.empty() ? 0.0 : m / static_cast<double>(x.size());
}

// Each channel in its output unit with the layout's zero.
std::vector<std::vector<double>> scaled_channels(const Log& log, const Layout& layout) {
  const std::size_t ns = log.t.size();
  std::vector<std::vector<double>> x(layout.channels.size(), std::vector<double>(ns));
  for (std::size_t i = 0; i < layout.channels.size(); ++i) {
    const Channel& c = layout.channels[i];
    for (std::size_t k = 0; k < ns; ++k) x[i][k] = c.gain * (log.raw[i][k] - c.zero);
  }
  return x;
}

// The plate's channels and its load: R_n, or R_s without normal cells.
struct PlateLoad {
  std::vector<std::size_t> idx;  // the plate's channels in the layout
  Role load_role = Role::normal;
  std::vector<double> load;  // the load's series as logged
};

PlateLoad plate_load(const Layout& layout, const std::vector<std::vector<double>>& x, std::size_t ns) {
  PlateLoad p;
  for (std::size_t i = 0; i < layout.channels.size(); ++i)
    if (plate(layout.channels[i].role)) p.idx.push_back(i);
  p.load_role = layout.has(Role::normal) ? Role::normal : Role::shear;
  p.load.assign(ns, 0.0);
  for (std::size_t i : p.idx)
    if (layout.channels[i].role == p.load_role)
      for (std::size_t k = 0; k < ns; ++k) p.load[k] += x[i][k];
  return p;
}

// The plate channels with their zeros taken off, and what the zeros leave in the uncertainty.
struct Zeroed {
  std::vector<std::vector<double>> y;  // zero-corrected plate channels
  std::vector<double> u_zero_at_c, dof_zero;
  double t_b = 0.0, t_a = 0.0;        // the tares' centres
  double zsum_b = 0.0, zsum_a = 0.0;  // the load's zero at them
};

// The zeros: tares before and after, a line between their centres. Adds each channel's zero and
// its warnings to r.
Zeroed take_zeros(const std::vector<double>& t, const Layout& layout, const PlateLoad& cells,
                  const std::vector<std::vector<double>>& x, ConditionReading& r) {
  const LogSegments& sg = r.segments;
  const std::size_t ns = t.size(), np = cells.idx.size();
  const double tc = sg.window.centre();
  const bool zb = sg.before.ok(), za = sg.after.ok();
  Zeroed out;
  out.t_b = zb ? sg.before.centre() : tc;
  out.t_a = za ? sg.after.centre() : tc;
  const double t_b = out.t_b, t_a = out.t_a;
  out.y.resize(np);
  out.u_zero_at_c.assign(np, 0.0);
  out.dof_zero.assign(np, kInfiniteDof);
  for (std::size_t j = 0; j < np; ++j) {
    const Channel& c = layout.channels[cells.idx[j]];
    const auto& xi = x[cells.idx[j]];
    ChannelZero z;
    z.column = c.column;
    CorrelatedMean mb, ma;
    if (zb) mb = correlated_mean(t, xi, sg.before.start, sg.before.end);
    if (za) ma = correlated_mean(t, xi, sg.after.start, sg.after.end);
    const bool okb = zb && std::isfinite(mb.se), oka = za && std::isfinite(ma.se);
    z.from_layout = !okb && !oka;
    z.before = okb ? mb.mean : (oka ? ma.mean : 0.0);
    z.after = oka ? ma.mean : z.before;
    z.u_before = okb ? mb.se : (oka ? ma.se : 0.0);
    z.u_after = oka ? ma.se : z.u_before;
    if (okb && oka) {
      z.drift = z.after - z.before;
      z.u_drift = std::hypot(z.u_before, z.u_after);
      const double s4 = std::pow(z.u_before, 4) / mb.dof + std::pow(z.u_after, 4) / ma.dof;
      z.dof = s4 > 0.0 ? std::pow(z.u_drift, 4) / s4 : kInfiniteDof;
      z.drift_flag = std::abs(z.drift) > t_quantile(kFlagAlpha, z.dof) * z.u_drift;
    } else {
      z.dof = okb ? mb.dof : (oka ? ma.dof : kInfiniteDof);
    }
    // The zero at time s, and its uncertainty at the window's centre.
    const double span = t_a - t_b;
    auto zero_at = [&](double s) {
      if (!(okb && oka) || !(span > 0.0)) return z.before;
      return z.before + (z.after - z.before) * (s - t_b) / span;
    };
    const double a = (okb && oka && span > 0.0) ? std::clamp((tc - t_b) / span, 0.0, 1.0) : 0.0;
    out.u_zero_at_c[j] = (okb && oka) ? std::hypot((1.0 - a) * z.u_before, a * z.u_after) : z.u_before;
    out.dof_zero[j] = okb && oka ? z.dof : (okb ? mb.dof : (oka ? ma.dof : kInfiniteDof));
    out.y[j].resize(ns);
    for (std::size_t k = 0; k < ns; ++k) out.y[j][k] = xi[k] - zero_at(t[k]);
    if (c.role == cells.load_role) {
      out.zsum_b += zero_at(t_b);
      out.zsum_a += zero_at(t_a);
    }
    if (z.from_layout)
      r.warnings.push_back(fmt::format("{}: no unloaded part to take its zero from; the layout's zero is used, unchecked",
                                       c.column));
    if (z.drift_flag)
      r.warnings.push_back(fmt::format(
          "{}: the zero drifts by {:+.4g} ± {:.2g} N between the tares ({:.1f} s and {:.1f} s); corrected as a straight line",
          c.column, z.drift, z.u_drift, t_b, t_a));
    r.zeros.push_back(z);
  }
  return out;
}

// The channels' window means, the quantities there, their gradients with respect to the means, and
// each quantity's series linearised about them.
struct Linearised {
  std::vector<double> m;
  PlateQuantities pq;
  std::vector<double> f0;
  std::vector<std::vector<double>> grad;    // [quantity][channel]
  std::vector<std::vector<double>> series;  // [quantity][sample]
};

Linearised linearise(const std::vector<double>& t, const Layout& layout, const PlateLoad& cells, const Zeroed& zeroed,
                     const Span& win) {
  const std::size_t ns = t.size(), np = cells.idx.size();
  Linearised l;
  l.m.resize(np);
  for (std::size_t j = 0; j < np; ++j) l.m[j] = mean_in(t, zeroed.y[j], win);
  l.pq = plate_quantities(layout, cells.idx);
  l.f0 = l.pq.f(l.m);
  l.grad.assign(l.f0.size(), std::vector<double>(np));
  for (std::size_t j = 0; j < np; ++j) {
    const double h = std::max(1e-6, 1e-6 * std::abs(l.m[j]));
    std::vector<double> mp = l.m, mm = l.m;
    mp[j] += h;
    mm[j] -= h;
    const auto fp = l.pq.f(mp), fm = l.pq.f(mm);
    for (std::size_t q = 0; q < l.f0.size(); ++q) l.grad[q][j] = (fp[q] - fm[q]) / (2.0 * h);
  }
  l.series.assign(l.f0.size(), std::vector<double>(ns));
  for (std::size_t q = 0; q < l.f0.size(); ++q)
    for (std::size_t k = 0; k < ns; ++k) {
      double v = l.f0[q];
      for (std::size_t j = 0; j < np; ++j) v += l.grad[q][j] * (zeroed.y[j][k] - l.m[j]);
      l.series[q][k] = v;
    }
  return l;
}

// The load's creep: a fraction of the load at its start per second.
struct Creep {
  bool found = false;
  double kappa = 0.0, u_kappa = 0.0, dof = kInfiniteDof;
  double lever = 0.0;  // from the load's start to the window's centre, s
};

// Creep is judged on the plate's load (R_n, or R_s without normal cells), where it stands
// clearest above the noise; the cells are taken to creep alike, by the same fraction of their
// load a second, so a creep found there corrects every force by that fraction and leaves the
// impact point (a ratio of forces) as it is.
Creep find_creep(const std::vector<double>& t, const PlateLoad& cells, const Linearised& l, const LogSegments& sg) {
  const Span& win = sg.window;
  const Quantity load_q = cells.load_role == Role::normal ? Quantity::normal_force : Quantity::shear_force;
  Creep c;
  c.lever = win.centre() - sg.load_start;
  for (std::size_t q = 0; q < l.f0.size(); ++q) {
    if (l.pq.names[q] != load_q) continue;
    const CorrelatedMean st = correlated_mean(t, l.series[q], win.start, win.end);
    if (st.blocks >= 3 && std::isfinite(st.se_slope) && st.se_slope > 0.0 && l.f0[q] != 0.0) {
      c.found = std::abs(st.slope) > t_quantile(kFlagAlpha, st.slope_dof) * st.se_slope;
      // The fraction per second relative to the load at its start.
      const double at_start = l.f0[q] - st.slope * c.lever;
      c.kappa = st.slope / at_start;
      c.u_kappa = st.se_slope / std::abs(at_start);
      c.dof = st.slope_dof;
    }
  }
  return c;
}

// Quantity q's reading: its value (corrected for creep) and its uncertainty budget (scatter, creep,
// zero, calibration, resolution). Adds its warnings to r.
QuantityReading read_quantity(std::size_t q, const std::vector<double>& t, const Layout& layout, const PlateLoad& cells,
                              const Zeroed& zeroed, const Linearised& l, const Creep& creep, ConditionReading& r) {
  const Span& win = r.segments.window;
  QuantityReading qr;
  qr.quantity = l.pq.names[q];
  qr.stats = correlated_mean(t, l.series[q], win.start, win.end);
  qr.value = l.f0[q];
  std::vector<UncertaintyPart> parts;
  double scatter = qr.stats.se, scatter_dof_used = qr.stats.dof;
  if (qr.stats.blocks >= 3 && std::isfinite(qr.stats.se_slope)) {
    qr.creep_change = qr.stats.slope * win.length();
    qr.creep_u = qr.stats.se_slope * win.length();
  }
  const bool force = qr.quantity != Quantity::impact_point_y;
  if (creep.found && force) {
    qr.creep = true;
    const CorrelatedMean d = correlated_mean(t, l.series[q], win.start, win.end, true);
    // value = at_start (1 + kappa lever): the load at its start is value / (1 + kappa lever).
    const double at_start = qr.value / (1.0 + creep.kappa * creep.lever);
    qr.creep_correction = at_start - qr.value;
    qr.value = at_start;
    scatter = d.se;
    scatter_dof_used = d.dof;
    parts.push_back({"creep", std::abs(at_start) * creep.u_kappa * creep.lever, creep.dof});
    r.warnings.push_back(fmt::format(
        "{}: creeps by {:+.4g} ± {:.2g} {} over the window ({:.1f}-{:.1f} s, {:+.2f} % a second of the load); "
        "corrected back to the load's start at {:.1f} s ({:+.4g} {})",
        name(qr.quantity), qr.creep_change * info(qr.quantity).to_boundary, qr.creep_u * info(qr.quantity).to_boundary,
        info(qr.quantity).unit, win.start, win.end, 100.0 * creep.kappa, r.segments.load_start,
        qr.creep_correction * info(qr.quantity).to_boundary, info(qr.quantity).unit));
  }
  parts.insert(parts.begin(), {"scatter", std::isfinite(scatter) ? scatter : 0.0, scatter_dof_used});
  double u_zero2 = 0.0, s4 = 0.0, u_cal2 = 0.0, u_res2 = 0.0;
  for (std::size_t j = 0; j < cells.idx.size(); ++j) {
    const Channel& c = layout.channels[cells.idx[j]];
    const double zj = l.grad[q][j] * zeroed.u_zero_at_c[j];
    u_zero2 += zj * zj;
    if (std::isfinite(zeroed.dof_zero[j]) && zeroed.dof_zero[j] > 0.0) s4 += std::pow(zj, 4) / zeroed.dof_zero[j];
    const double cj = l.grad[q][j] * l.m[j] * c.gain_u;
    u_cal2 += cj * cj;
    // The logger's step: rectangular, averaged down over the independent samples only when the
    // noise is larger than the step (otherwise every sample rounds alike).
    const double step = std::abs(c.gain) * c.resolution / std::sqrt(12.0);
    const double sd_j = qr.stats.sd;  // the quantity's scatter stands in for the channel's
    const double rj = l.grad[q][j] * step / ((sd_j > std::abs(c.gain) * c.resolution) ? std::sqrt(qr.stats.n_eff) : 1.0);
    u_res2 += rj * rj;
  }
  if (u_zero2 > 0.0) parts.push_back({"zero", std::sqrt(u_zero2), s4 > 0.0 ? u_zero2 * u_zero2 / s4 : kInfiniteDof});
  if (u_cal2 > 0.0) parts.push_back({"calibration", std::sqrt(u_cal2), kInfiniteDof});
  if (u_res2 > 0.0) parts.push_back({"resolution", std::sqrt(u_res2), kInfiniteDof});
  qr.budget = combine(parts);
  if (qr.budget.too_short)
    r.warnings.push_back(fmt::format(
        "{}: the log is too short to say its own uncertainty: {:.1f} effective degrees of freedom ({} batches of {:.2f} s, "
        "{:.1f} independent samples); u widened x{:.2f} to {:.3g} {}",
        name(qr.quantity), qr.budget.dof, qr.stats.blocks, qr.stats.block, qr.stats.n_eff, qr.budget.widening,
        qr.budget.u * info(qr.quantity).to_boundary, info(qr.quantity).unit));
  return qr;
}

// The belt's own channels against the record: added to r.checks, a warning when they disagree.
void check_operating_channels(const std::vector<double>& t, const Layout& layout, const std::vector<std::vector<double>>& x,
                              std::optional<double> recorded_speed, std::optional<double> recorded_flow,
                              ConditionReading& r) {
  const Span& win = r.segments.window;
  for (std::size_t i = 0; i < layout.channels.size(); ++i) {
    const Channel& c = layout.channels[i];
    if (plate(c.role)) continue;
    const std::optional<double> rec = c.role == Role::belt_speed ? recorded_speed : recorded_flow;
    const double to_si = c.role == Role::mass_flow ? 1.0 / 3.6 : 1.0;  // t/h -> kg/s
    const CorrelatedMean cm = correlated_mean(t, x[i], win.start, win.end);
    OperatingCheck ck;
    ck.role = c.role;
    ck.column = c.column;
    ck.logged = cm.mean * to_si;
    const double se = std::isfinite(cm.se) ? cm.se * to_si : 0.0;
    ck.u = std::hypot(se, ck.logged * c.gain_u);
    if (!rec || !(*rec > 0.0)) continue;
    ck.recorded = *rec;
    const double u_test = std::max(ck.u, 1e-12);
    ck.off = std::abs(ck.logged - ck.recorded) > 3.0 * u_test;
    const double shown_scale = c.role == Role::mass_flow ? 3.6 : 1.0;
    if (ck.off)
      r.warnings.push_back(fmt::format(
          "the recorded {} is {:.4g} {}, its own channel {} reads {:.4g} ± {:.2g} {} ({:+.1f} %): check the record "
          "before any diagnosis",
          c.role == Role::belt_speed ? "belt speed" : "mass flow", ck.recorded * shown_scale, unit(c.role), c.column,
          ck.logged * shown_scale, ck.u * shown_scale, unit(c.role), 100.0 * ck.relative()));
    r.checks.push_back(ck);
  }
}

}  // namespace

ConditionReading read_condition(const Log& log, const Layout& layout, const std::string& condition,
                                std::optional<double> recorded_speed, std::optional<double> recorded_flow) {
  ConditionReading r;
  r.condition = condition;
  r.file = log.file;
  r.dt = log.dt;
  const auto& t = log.t;
  const auto x = scaled_channels(log, layout);
  const PlateLoad cells = plate_load(layout, x, t.size());
  r.segments = find_segments(t, cells.load);
  for (const auto& w : r.segments.warnings) r.warnings.push_back(w);
  if (!r.segments.loaded || !r.segments.window.ok()) return r;

  const Zeroed zeroed = take_zeros(t, layout, cells, x, r);
  const Linearised l = linearise(t, layout, cells, zeroed, r.segments.window);
  const Creep creep = find_creep(t, cells, l, r.segments);
  const Quantity load_q = cells.load_role == Role::normal ? Quantity::normal_force : Quantity::shear_force;
  for (std::size_t q = 0; q < l.f0.size(); ++q) {
    QuantityReading qr = read_quantity(q, t, layout, cells, zeroed, l, creep, r);
    if (qr.quantity == load_q) r.trend_slope = qr.stats.slope;
    r.quantities.push_back(std::move(qr));
  }
  check_operating_channels(t, layout, x, recorded_speed, recorded_flow, r);

  // The chart: the load as logged, thinned to about 600 points.
  const std::size_t stride = std::max<std::size_t>(1, t.size() / 600);
  for (std::size_t k = 0; k < t.size(); k += stride) {
    r.chart_t.push_back(t[k]);
    r.chart_load.push_back(cells.load[k]);
  }
  r.zero_t0 = zeroed.t_b;
  r.zero_t1 = zeroed.t_a;
  r.zero_v0 = zeroed.zsum_b;
  r.zero_v1 = zeroed.zsum_a;
  return r;
}

}  // namespace chutelab::logs
