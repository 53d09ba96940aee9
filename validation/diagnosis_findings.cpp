// What the diagnosis says about its recommended explanation: what it leaves (noise or not, per
// quantity), the expensive model's profile of its strength, the readings that pull it, the outliers,
// each quantity's shift, the record's scope, and the rivals these data cannot tell from it.
#include "validation/diagnosis.h"

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <fmt/format.h>
#include <gsl/gsl_cdf.h>
#include <map>
#include <set>
#include <thread>

#include "analytical/transfer_station.h"
#include "core/campaign.h"
#include "core/input_error.h"
#include "core/progress.h"
#include "effects/registry.h"
#include "effects/at_condition.h"
#include "validation/diagnosis_stage.h"
#include "validation/misfit.h"
#include "validation/noise_model.h"
#include "validation/strength_fit.h"

namespace chutelab::validation {

namespace detail {

// Is what an explanation leaves noise? Per quantity (outside discrepancies): its excess scatter, its
// bias and its trend with an operating variable, Bonferroni over quantities and tests; and, while
// the uncertainties stand as stated, the whole chi^2.
std::vector<Leftover> leftovers_of(const Stage& s, const std::vector<double>& r, double k, double chi2,
                                   const Drivers& drivers) {
  std::vector<Leftover> out;
  const auto scatter = group_scatter(s.m, s.nm, r, drivers);
  // Half the family's alpha (the other half flags discrepant quantities, validation/noise_model.h),
  // shared among the quantities' three tests and the whole chi^2.
  const double alpha = 0.5 * s.opt.alpha;
  const double tests = 3.0 * static_cast<double>(std::max<std::size_t>(1, scatter.size())) + 1.0;
  for (const auto& g : scatter) {
    if (g.n == 0 || s.nm.discrepancy[g.group] > 0.0) continue;
    const double p_trend = std::min(1.0, g.p_trend * static_cast<double>(drivers.names.size()));
    const double p = std::min({g.p_excess, g.p_bias, p_trend});
    if (p * tests >= alpha) continue;
    const auto& grp = s.m.groups()[g.group];
    Leftover l;
    l.quantity = grp.quantity;
    l.model = s.m.models()[grp.model]->name();
    l.n = g.n;
    l.p = p;
    l.pattern = p == g.p_bias ? "bias" : p == g.p_excess ? "scatter" : g.trend_driver;
    out.push_back(l);
  }
  if (out.empty() && s.nm.scale <= 1.0 && gsl_cdf_chisq_Q(chi2, s.dof(k)) * tests < alpha) {
    Leftover l;
    l.quantity = "all";
    l.n = static_cast<int>(s.n);
    l.p = gsl_cdf_chisq_Q(chi2, s.dof(k));
    l.pattern = "scatter";
    out.push_back(l);
  }
  return out;
}

// Where each effect of an explanation finds its evidence: the fall of chi^2 from the explanation
// with that effect switched off to the explanation. When nine tenths of it come from one quantity
// and the effect makes another quantity significantly worse (at the family's alpha), it fixes one
// quantity at the expense of the rest: it stands in for an error in how the models predict that
// quantity. (An effect whose evidence lies in one quantity but fits the rest is not suspect.)
std::optional<Evidence> concentrated(const Stage& s, const Fx& fx, const std::vector<double>& v) {
  const auto r1 = s.cost.weighted(s.m.residuals(fx, v));
  for (std::size_t j = 0; j < fx.size(); ++j) {
    Evidence e;
    e.effect = j;
    auto off = v;
    off[j] = fx[j]->neutral;
    e.before = s.m.residuals(fx, off);
    const auto r0 = s.cost.weighted(e.before);
    std::vector<double> fall(s.m.groups().size(), 0.0);
    double total = 0.0;
    for (std::size_t i = 0; i < r0.size(); ++i) fall[s.m.points()[i].group] += r0[i] * r0[i] - r1[i] * r1[i];
    for (double f : fall) total += std::max(0.0, f);
    e.group = static_cast<std::size_t>(std::max_element(fall.begin(), fall.end()) - fall.begin());
    e.share = total > 0.0 ? fall[e.group] / total : 0.0;
    double worse = 0.0;
    for (double f : fall) worse += std::max(0.0, -f);
    if (total > 0.0 && e.share >= 0.9 && worse > gsl_cdf_chisq_Qinv(s.opt.alpha, 1.0)) return e;
  }
  return std::nullopt;
}


namespace {

struct ConditionFit {
  std::vector<double> estimate, uncertainty, drop;
};

// Each condition's error of one input, fitted on its own: the conditions' residuals depend on their
// own station only, so the joint fit of n errors is n fits of one, and its chi^2 falls by the sum.
// Each fit reads its condition's points alone (a fit over the whole dataset would cost n times
// more, n^2 in all).
ConditionFit fit_per_condition(const Stage& s, const effects::EffectInfo& e) {
  ConditionFit out;
  const auto& stations = s.m.dataset().stations;
  for (std::size_t ci = 0; ci < stations.size(); ++ci) {
    const effects::EffectInfo c = effects::at_condition(e, stations[ci].condition);
    const Fx fx = {&c};
    const Cost part = s.cost.only({ci});
    const StrengthFit f = fit_strengths(part, fx);
    out.estimate.push_back(f.estimate[0]);
    out.uncertainty.push_back(f.uncertainty[0]);
    out.drop.push_back(std::max(0.0, part.chi2({}, {}) - f.chi2));
  }
  return out;
}

// For the recommended record: one error for the rig, or one per condition? Analytical models only:
}  // namespace

// For the recommended record: one error for the rig, or one per condition? Analytical models only:
// with a DEM each condition's candidate would need probe runs of its own.
std::optional<RecordScope> record_scope_of(const Stage& s, const EffectFit* best) {
  if (s.m.source().has_expensive() || !best || best->effects.size() != 1 || !best->is_record()) return std::nullopt;
  const auto& stations = s.m.dataset().stations;
  const double n = static_cast<double>(stations.size());
  const auto* e = effects::find(best->effects[0]);
  if (n < 2 || !e) return std::nullopt;  // a record at one condition is already said to be one
  const ConditionFit f = fit_per_condition(s, *e);
  RecordScope r;
  r.input = e->name;
  r.unit = e->unit;
  for (std::size_t c = 0; c < stations.size(); ++c) r.conditions.push_back(stations[c].condition);
  r.estimate = f.estimate;
  r.uncertainty = f.uncertainty;
  double drop = 0.0;
  for (double d : f.drop) drop += d;
  r.rig_wide_chi2 = best->chi2_after;
  r.per_condition_chi2 = std::max(0.0, s.chi2_0 - drop);
  r.p = s.p_improvement(r.rig_wide_chi2 - r.per_condition_chi2, n - 1.0, r.per_condition_chi2);
  r.differs = r.p < s.opt.alpha;
  return r;
}

// The expensive model's own chi^2 at a few strengths around a single's estimate: the estimate and sd
// from its curvature, not from the linear signature.
void profile_best(EffectFit& f, const Stage& s, int jobs) {
  const auto* e = effects::find_candidate(f.effects[0]);
  if (s.m.source().signature(*e) == PredictionSource::Signature::none) return;  // applied exactly already
  const Fx fx = {e};
  auto chi2_at = [&](double v) {
    const std::vector<double> at = {v};
    s.m.source().prepare_exact(fx, at, jobs, fmt::format("a point of {}'s profile (its chi^2 from real runs)", e->name));
    return s.cost.chi2_of(s.m.residuals_exact(fx, at));
  };
  const double span = e->upper - e->lower;
  const double sd = std::isfinite(f.uncertainty[0]) ? f.uncertainty[0] : span;
  const double step = std::clamp(2.0 * sd, 0.01 * span, 0.25 * span);
  // The confirming run at the estimate is the profile's first point.
  std::vector<std::pair<double, double>> known;
  if (f.chi2_from_signatures) known.emplace_back(f.estimate[0], f.chi2_after);
  ProfileFit p = profile_strength(chi2_at, f.estimate[0], step, e->lower, e->upper, s.opt.profile_runs, known);
  f.profile = p;
  if (!p.bracketed) return;
  f.estimate[0] = p.estimate;
  f.uncertainty[0] = p.uncertainty;
  // The curvature is the quantities' sum. Where the ones that carry it scatter around the real runs
  // more than their uncertainties say (another code's forces a few % apart, which no stated
  // uncertainty holds), the curvature claims too much: the sd is widened by their Birge ratio,
  // weighted by each quantity's share of the curvature.
  const auto low = p.lowest();
  if (low != p.points.begin() && std::next(low) != p.points.end()) {
    const std::array<double, 3> x = {std::prev(low)->first, low->first, std::next(low)->first};
    std::array<std::vector<double>, 3> r;
    for (std::size_t k = 0; k < 3; ++k) r[k] = s.cost.weighted(s.m.residuals_exact(fx, std::vector<double>{x[k]}));
    double weight = 0.0, weighted = 0.0;
    for (const auto& g : s.m.groups()) {
      std::array<double, 3> c{};
      int n = 0;
      for (std::size_t i : g.points) {
        if (s.cost.weights()[i] <= 0.0) continue;
        ++n;
        for (std::size_t k = 0; k < 3; ++k) c[k] += r[k][i] * r[k][i];
      }
      if (n == 0) continue;
      const double a = ((c[2] - c[1]) / (x[2] - x[1]) - (c[1] - c[0]) / (x[1] - x[0])) / (x[2] - x[0]);
      if (!(a > 0.0)) continue;
      weight += a;
      weighted += a * c[1] / n;
    }
    double widened = weight > 0.0 && weighted / weight > 1.0 ? std::sqrt(weighted / weight) : 1.0;
    // And the readings' own verdict on the strength: the sandwich (HC3) variance of the real runs'
    // slope, sum over readings of their leave-one-out shifts, which does not take the stated
    // uncertainties on trust (a few readings that alone pull the strength by several sd widen it).
    double jj = 0.0;
    std::vector<double> slope(s.m.size(), 0.0);
    for (std::size_t i = 0; i < s.m.size(); ++i) {
      slope[i] = (r[2][i] - r[0][i]) / (x[2] - x[0]);
      jj += slope[i] * slope[i];
    }
    if (jj > 0.0 && p.uncertainty > 0.0) {
      double v = 0.0;
      for (std::size_t i = 0; i < s.m.size(); ++i) {
        const double h = slope[i] * slope[i] / jj;
        if (h < 1.0) v += std::pow(slope[i] * r[1][i] / jj / (1.0 - h), 2);
      }
      widened = std::max(widened, std::sqrt(v) / p.uncertainty);
    }
    if (widened > 1.0) {
      f.profile_widened = widened;
      f.uncertainty[0] *= widened;
    }
  }
  rescore(f, p.chi2, s);
}

// The recommended explanation's residuals: from the expensive model's real runs where it was run at
// (or, for a profile, next to) the fitted strength, else from the signatures.
std::vector<double> best_residuals(const Stage& s, const EffectFit* best) {
  if (!best || !best->chi2_from_signatures || !s.m.source().reruns_expensive()) return residuals_at(s.m, best);
  std::vector<double> at = best->estimate;
  if (best->profile && !best->profile->points.empty())
    at = {best->profile->lowest()->first};
  return s.m.residuals_exact(infos_of(*best), at);
}

namespace {

double weight_without_exclusion(const NoiseModel& nm, const Misfit& m, std::size_t i) {
  const auto& p = m.points()[i];
  return 1.0 / std::sqrt(nm.scale * nm.scale + std::pow(nm.discrepancy[p.group] / p.uncertainty, 2));
}

double to_boundary(const MisfitPoint& p) { return p.q ? info(*p.q).to_boundary : 1e3; }
}  // namespace


std::vector<Outlier> name_outliers(const Stage& s, const EffectFit* best, const std::vector<EffectFit>& singles) {
  std::vector<Outlier> out;
  const auto& m = s.m;
  const auto r = residuals_at(m, best);
  const auto pred = best ? m.predicted(infos_of(*best), best->estimate) : m.predicted({}, {});
  std::vector<std::vector<double>> others;
  others.push_back(m.residuals({}, {}));
  for (const auto& f : singles) others.push_back(m.residuals(infos_of(f), f.estimate));
  for (std::size_t i = 0; i < m.size(); ++i) {
    if (!s.nm.excluded[i]) continue;
    const auto& p = m.points()[i];
    const double w = weight_without_exclusion(s.nm, m, i);
    Outlier o;
    o.condition = m.dataset().stations[p.condition].condition;
    o.quantity = p.quantity;
    o.where = p.where;
    o.measured = p.measured * to_boundary(p);
    o.predicted = pred[i].value_or(0.0) * to_boundary(p);
    o.deviation = -r[i] * w;
    o.relative = pred[i] && *pred[i] != 0.0 ? (p.measured - *pred[i]) / std::abs(*pred[i]) : 0.0;
    o.closest = INFINITY;
    for (const auto& other : others) o.closest = std::min(o.closest, std::abs(other[i]) * w);
    o.records = records_for_reading(s, best, i);
    out.push_back(o);
  }
  return out;
}

// Readings that alone move a fitted strength by more than one sd: a linear leave-one-out estimate
// picks the few worth a real refit.
std::vector<Influence> influential(const Stage& s, const EffectFit& best) {
  const auto& m = s.m;
  const Fx fx = infos_of(best);
  const std::size_t k = fx.size();
  Eigen::MatrixXd J(m.size(), k);
  const auto r0 = s.cost.residuals(fx, best.estimate);
  for (std::size_t j = 0; j < k; ++j) {
    const double h = 1e-4 * (fx[j]->upper - fx[j]->lower);
    auto at = best.estimate;
    at[j] += h;
    const auto r1 = s.cost.residuals(fx, at);
    for (std::size_t i = 0; i < m.size(); ++i) J(i, j) = (r1[i] - r0[i]) / h;
  }
  const Eigen::MatrixXd JtJ = J.transpose() * J;
  Eigen::FullPivLU<Eigen::MatrixXd> lu(JtJ);
  if (!lu.isInvertible()) return {};
  const Eigen::MatrixXd C = lu.inverse();
  std::vector<std::pair<double, std::size_t>> suspects;
  for (std::size_t i = 0; i < m.size(); ++i) {
    if (s.cost.weights()[i] == 0.0) continue;
    const Eigen::VectorXd Ji = J.row(static_cast<Eigen::Index>(i)).transpose();
    const double h = Ji.dot(C * Ji);
    if (h >= 1.0) continue;
    const Eigen::VectorXd shift = C * Ji * r0[i] / (1.0 - h);
    double worst = 0.0;
    for (std::size_t j = 0; j < k; ++j)
      if (std::isfinite(best.uncertainty[j]) && best.uncertainty[j] > 0.0)
        worst = std::max(worst, std::abs(shift(static_cast<Eigen::Index>(j))) / best.uncertainty[j]);
    if (worst > 0.5) suspects.emplace_back(worst, i);
  }
  std::sort(suspects.rbegin(), suspects.rend());
  std::vector<Influence> out;
  for (std::size_t n = 0; n < suspects.size() && n < 5; ++n) {
    const std::size_t i = suspects[n].second;
    auto w = s.cost.weights();
    w[i] = 0.0;
    const auto refit = fit_strengths(Cost(m, w), fx, {StrengthRange::physical, {best.estimate}});
    for (std::size_t j = 0; j < k; ++j) {
      if (!(std::isfinite(best.uncertainty[j]) && best.uncertainty[j] > 0.0)) continue;
      const double shift = (refit.estimate[j] - best.estimate[j]) / best.uncertainty[j];
      if (std::abs(shift) <= 1.0) continue;
      const auto& p = m.points()[i];
      out.push_back({m.dataset().stations[p.condition].condition, p.quantity, p.where, best.parameters[j], shift});
    }
  }
  return out;
}

// Each quantity's mean error before and after the recommended explanation, in its own units.
// `exact`: the explanation's residuals from real runs, where there are some (else its predictions).
std::vector<QuantityShift> shifts_of(const Stage& s, const Fx& fx, const std::vector<double>& strengths,
                                     const std::vector<double>& exact, const std::string& only) {
  const auto& m = s.m;
  const auto before = m.predicted({}, {});
  auto after = fx.empty() ? before : m.predicted(fx, strengths);
  if (exact.size() == m.size())
    for (std::size_t i = 0; i < m.size(); ++i) after[i] = m.points()[i].measured + exact[i] * m.points()[i].uncertainty;
  std::vector<QuantityShift> out;
  for (const auto& g : m.groups()) {
    QuantityShift q;
    q.quantity = g.quantity;
    const auto& p0 = m.points()[g.points.front()];
    if (p0.q) {
      q.symbol = info(*p0.q).symbol;
      q.label = info(*p0.q).label;
      q.unit = info(*p0.q).unit;
      q.relative = *p0.q != Quantity::impact_point_y;
    } else {
      q.symbol = g.quantity;
      q.label = fmt::format("{} stream limit", g.quantity.substr(11, g.quantity.find("_y_mm") - 11));
      q.unit = "mm";
    }
    for (std::size_t i : g.points) {
      if (s.nm.excluded[i]) continue;
      const auto& p = m.points()[i];
      if (!only.empty() && m.dataset().stations[p.condition].condition != only) continue;
      const double scale = to_boundary(p);
      q.before += (before[i].value_or(0.0) - p.measured) * scale;
      q.after += (after[i].value_or(0.0) - p.measured) * scale;
      if (p.measured != 0.0) {
        q.before_relative += (before[i].value_or(0.0) - p.measured) / std::abs(p.measured);
        q.after_relative += (after[i].value_or(0.0) - p.measured) / std::abs(p.measured);
      }
      ++q.n;
    }
    if (q.n == 0) continue;
    q.before /= q.n, q.after /= q.n, q.before_relative /= q.n, q.after_relative /= q.n;
    out.push_back(q);
  }
  return out;
}

std::vector<Discrepancy> model_form_of(const Stage& s, const std::vector<QuantityShift>& shifts) {
  std::vector<Discrepancy> out;
  for (std::size_t g = 0; g < s.m.groups().size(); ++g) {
    if (s.nm.discrepancy[g] <= 0.0) continue;
    const auto& grp = s.m.groups()[g];
    Discrepancy d;
    d.quantity = grp.quantity;
    d.model = s.m.models()[grp.model]->name();
    d.tau = s.nm.discrepancy[g] * to_boundary(s.m.points()[grp.points.front()]);
    for (const auto& q : shifts)
      if (q.quantity == grp.quantity) d.n = q.n, d.mean_error = q.after, d.mean_relative = q.after_relative;
    out.push_back(d);
  }
  return out;
}

void fill_leftovers(std::vector<Leftover>& left, const std::vector<QuantityShift>& shifts) {
  for (auto& l : left)
    for (const auto& q : shifts)
      if (q.quantity == l.quantity) l.mean_error = q.after, l.mean_relative = q.after_relative;
}

// Residual patterns: for each quantity, the normalised residuals of the models as they are,
// against the operating variables an engineer would suspect.
std::vector<ResidualPattern> residual_patterns(const Misfit& m, const std::vector<double>& r) {
  const Dataset& d = m.dataset();
  std::vector<double> speed, flow, tflight, drop;
  for (const auto& st : d.stations) {
    speed.push_back(st.belt_speed);
    flow.push_back(st.mass_flow * 3.6);
    try {
      const auto a = analytical::analyse_transfer(st);
      tflight.push_back(a.flight_time());
      drop.push_back(a.drop_height() * 1e3);
    } catch (const std::exception&) {
      tflight.push_back(0.0);
      drop.push_back(0.0);
    }
  }
  std::vector<ResidualPattern> out;
  for (const auto& g : m.groups()) {
    std::vector<double> z, s, f, t, h;
    for (std::size_t i : g.points) {
      const auto c = m.points()[i].condition;
      z.push_back(r[i]);
      s.push_back(speed[c]), f.push_back(flow[c]), t.push_back(tflight[c]), h.push_back(drop[c]);
    }
    const int n = static_cast<int>(z.size());
    double mean = 0, ss = 0;
    for (double x : z) mean += x, ss += x * x;
    mean /= n;
    const double rms = std::sqrt(ss / n);
    // A bias is notable when the mean normalised residual is 3 standard errors from zero; a trend
    // when the residuals are large (RMS > 2) and line up with a driver (|r| >= 0.7).
    const bool bias = std::abs(mean) > 3.0 / std::sqrt(n);
    const std::vector<std::pair<std::string, const std::vector<double>*>> drivers = {
        {"belt speed", &s}, {"mass flow", &f}, {"flight time", &t}, {"drop height", &h}};
    for (const auto& [dn, dv] : drivers) {
      ResidualPattern p;
      p.model = m.models()[g.model]->name();
      p.quantity = g.quantity;
      p.driver = dn;
      p.n = n;
      p.mean_normalised = mean;
      p.rms_normalised = rms;
      double ma = 0, mb = 0;
      for (int i = 0; i < n; ++i) ma += z[i], mb += (*dv)[i];
      ma /= n, mb /= n;
      double sab = 0, saa = 0, sbb = 0;
      for (int i = 0; i < n; ++i)
        sab += (z[i] - ma) * ((*dv)[i] - mb), saa += (z[i] - ma) * (z[i] - ma), sbb += ((*dv)[i] - mb) * ((*dv)[i] - mb);
      p.correlation = n >= 3 && saa > 0 && sbb > 0 ? sab / std::sqrt(saa * sbb) : 0.0;
      p.notable = bias || (rms > 2.0 && std::abs(p.correlation) >= 0.7);
      out.push_back(p);
    }
  }
  return out;
}



// The change a fitted candidate makes to every normalised residual.
std::vector<double> fitted_change(const Misfit& m, const EffectFit& f, const std::vector<double>& r0) {
  auto r = m.residuals(infos_of(f), f.estimate);
  for (std::size_t i = 0; i < r.size(); ++i) r[i] -= r0[i];
  return r;
}


double cosine(const std::vector<double>& a, const std::vector<double>& b) {
  double ab = 0, aa = 0, bb = 0;
  for (std::size_t i = 0; i < a.size(); ++i) ab += a[i] * b[i], aa += a[i] * a[i], bb += b[i] * b[i];
  return aa > 0 && bb > 0 ? ab / std::sqrt(aa * bb) : 0.0;
}

// Which measurement tells two fitted explanations apart: the quantity and condition where their
// predictions differ most, in units of the uncertainty such a measurement has in this dataset
// (where a quantity is not measured, 2 % of a force, 0.05 m/s or 3 mm, the resolution of the
// reference study's instruments). With `unmeasured_only`, the quantities this dataset lacks.
std::vector<Discriminator> discriminators(const Misfit& m, const EffectFit& a, const EffectFit& b, bool unmeasured_only) {
  const auto pa = m.source().predict(infos_of(a), a.estimate), pb = m.source().predict(infos_of(b), b.estimate);
  std::map<Quantity, double> typical;
  for (const auto& meas : m.dataset().measurements)
    if (meas.uncertainty) typical[meas.quantity] = std::max(typical[meas.quantity], *meas.uncertainty);
  std::map<Quantity, Discriminator> best;
  for (std::size_t c = 0; c < pa.size(); ++c)
    for (std::size_t k = 0; k < pa[c].size(); ++k)
      for (Quantity q : kAllQuantities) {
        const auto &va = pa[c][k].values[q], &vb = pb[c][k].values[q];
        const bool measured = typical.count(q) > 0;
        if (!va || !vb || (unmeasured_only && measured)) continue;
        double u = measured ? typical[q] : 0.0;
        if (u <= 0.0)
          u = q == Quantity::impact_point_y ? 3e-3
              : (q == Quantity::impact_velocity || q == Quantity::exit_velocity) ? 0.05
                                                                                  : std::max(0.02 * std::abs(*va), 0.1);
        const double sep = std::abs(*va - *vb) / u;
        auto& d = best[q];
        if (sep <= d.separation) continue;
        const double sc = info(q).to_boundary;
        d = {a.label(), b.label(), std::string(name(q)), m.dataset().stations[c].condition, m.models()[k]->name(),
             std::string(info(q).unit), *va * sc, *vb * sc, sep, measured};
      }
  std::vector<Discriminator> out;
  for (const auto& [q, d] : best)
    if (d.separation > 0.0) out.push_back(d);
  std::sort(out.begin(), out.end(), [](const auto& x, const auto& y) { return x.separation > y.separation; });
  return out;
}

namespace {

// Candidates about as good as the best, and those that move the data in proportion to it.
// Candidates about as good as the best, and those that move the data in proportion to it. For an
// explanation by several causes, each cause's twins: a belt speed record named beside a plate
// distance is as much a belt slip as it is a belt speed, when these data cannot tell the two apart.
// About as good means about the same chi^2: a record's implausibility orders the ranking, but it is
// no evidence that the data tell a record from a physical effect that fits as well.
// The records at the same condition that move its readings in proportion to a cause wrong at one
// condition (a pulley diameter and a height datum there), with the other causes held.
void condition_twins(DiagnosisResult& out, const Stage& s, const EffectFit& best, const std::vector<double>& r0) {
  const auto& stations = s.m.dataset().stations;
  for (std::size_t j = 0; j < best.effects.size(); ++j) {
    const auto split = effects::split_condition(best.effects[j]);
    const std::string& input = split.first;
    const std::string& condition = split.second;
    if (condition.empty()) continue;
    const auto at = std::find_if(stations.begin(), stations.end(), [&](const Station& st) { return st.condition == condition; });
    if (at == stations.end()) continue;
    const Cost part = s.cost.only({static_cast<std::size_t>(at - stations.begin())});
    Fx others;
    std::vector<double> held;
    const Fx all = infos_of(best);
    for (std::size_t k = 0; k < all.size(); ++k)
      if (k != j) others.push_back(all[k]), held.push_back(best.estimate[k]);
    auto single = [&](const effects::EffectInfo* e, double v) {
      EffectFit f;
      f.effects = {e->name};
      f.parameters = {e->parameter};
      f.estimate = {v};
      f.uncertainty = {0.0};
      return f;
    };
    const EffectFit mine = single(all[j], best.estimate[j]);
    const auto d_mine = fitted_change(s.m, mine, r0);
    Fx with_mine = others;
    with_mine.push_back(all[j]);
    std::vector<double> at_mine = held;
    at_mine.push_back(best.estimate[j]);
    const double chi2_mine = part.chi2(with_mine, at_mine);
    for (const auto& e : effects::library()) {
      if (e.kind != effects::EffectInfo::Kind::record || e.name == input) continue;
      const auto* twin = effects::find_candidate(e.name + "@" + condition);
      const Held h = fit_held(part, others, held, twin);
      if (h.chi2 - chi2_mine > std::max(4.0, 0.05 * chi2_mine)) continue;
      const EffectFit other = single(twin, h.estimate);
      if (std::abs(cosine(d_mine, fitted_change(s.m, other, r0))) < s.opt.proportional_cosine) continue;
      auto d = discriminators(s.m, mine, other, true);
      if (d.empty()) d.push_back({mine.label(), other.label(), "", "", "", "", 0, 0, 0, false});
      for (auto& x : d) {
        x.model = "proportional";
        out.ties.push_back(x);
      }
    }
  }
}

}  // namespace

std::pair<double, double> chi2_alike(const EffectFit& a, const EffectFit& b) {
  auto signature_only = [](const EffectFit& f) { return f.signature == "own runs" || f.signature == "analytical only"; };
  if (a.chi2_from_signatures && !b.chi2_from_signatures && signature_only(b)) return {*a.chi2_from_signatures, b.chi2_after};
  if (b.chi2_from_signatures && !a.chi2_from_signatures && signature_only(a)) return {a.chi2_after, *b.chi2_from_signatures};
  return {a.chi2_after, b.chi2_after};
}

void ties_of(DiagnosisResult& out, const Stage& s, const std::vector<double>& r0) {
  const EffectFit* best = out.best();
  if (best) condition_twins(out, s, *best, r0);
  std::vector<const EffectFit*> named;
  if (best && best != &out.singles.front()) {
    for (const auto& cause : best->effects)
      for (const auto& f : out.singles)
        if (f.effects[0] == cause) named.push_back(&f);
  } else {
    named.push_back(&out.singles.front());
  }
  for (const EffectFit* top : named) {
    const auto d_top = fitted_change(s.m, *top, r0);
    for (const auto& f : out.singles) {
      if (&f == top || (best && std::count(best->effects.begin(), best->effects.end(), f.effects[0]))) continue;
      if (!f.significant) continue;
      const auto [chi2_top, chi2_f] = chi2_alike(*top, f);
      const bool tie = named.size() == 1 && chi2_f - chi2_top < s.opt.tie_margin_bic;
      // Proportional: the data cannot tell them apart, whatever the ranking.
      const bool proportional = std::abs(cosine(d_top, fitted_change(s.m, f, r0))) >= s.opt.proportional_cosine &&
                                chi2_f - chi2_top <= std::max(4.0, 0.05 * chi2_top);
      if (!tie && !proportional) continue;
      auto d = discriminators(s.m, *top, f, proportional);
      if (d.empty()) d.push_back({top->label(), f.label(), "", "", "", "", 0, 0, 0, false});
      d.front().measured_here = !proportional && d.front().measured_here;
      if (proportional) d.front().model = "proportional";
      if (tie) out.indistinguishable.push_back(f.label());
      out.ties.push_back(d.front());
      for (std::size_t j = 1; j < d.size() && proportional; ++j) {
        d[j].model = "proportional";
        out.ties.push_back(d[j]);
      }
    }
  }
}

}  // namespace detail
}  // namespace chutelab::validation
