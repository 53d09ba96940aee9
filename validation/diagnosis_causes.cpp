// Every cause the data support (validation/diagnosis_stage.h, more_causes). Real rigs have several
// things wrong at once (a drive set low and a plate moved; drag and slip), so the search does not stop
// at the best single: each step adds to the explanation so far the candidate whose joint fit lowers
// chi^2 most, a library candidate or a recorded input wrong at one condition, and keeps it while the
// fall is significant against the explanation without it. In the noise model's first round this runs
// at the stated uncertainties, so that structure is found before any scatter is conceded to noise.
#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <gsl/gsl_cdf.h>
#include <map>
#include <numeric>
#include <set>

#include "effects/at_condition.h"
#include "validation/diagnosis_stage.h"

namespace chutelab::validation::detail {
namespace {

// More causes than this are not sought: each costs a strength, and three already need a dataset of
// many conditions and quantities to be told apart.
constexpr std::size_t kMaxCauses = 3;
// Records at one condition fitted for real in a step: the most promising by a first-order screen.
constexpr std::size_t kScreenedAtCondition = 8;

double dot(const std::vector<double>& a, const std::vector<double>& b) {
  double t = 0.0;
  for (std::size_t k = 0; k < a.size(); ++k) t += a[k] * b[k];
  return t;
}

bool has(const EffectFit& f, const std::string& name) {
  return std::find(f.effects.begin(), f.effects.end(), name) != f.effects.end();
}

// The added cause of `f` is a record fitted within its plausible error: the record is right to
// within what it claims, whatever the test says (as for a single, EffectFit::within_plausible_error).
bool added_within_plausible_error(const EffectFit& f) {
  const std::size_t j = f.effects.size() - 1;
  return j < f.prior_width.size() && f.prior_width[j] > 0.0 && std::abs(f.estimate[j]) < f.prior_width[j];
}

// An explanation one cause larger than `base` (null: the models as they are), among `family`
// candidates this step looked at: its fall of chi^2 (the record's implausibility charged) tested with
// one more degree of freedom, Bonferroni over the family, and, beyond a first cause, by a clear BIC
// margin over the base.
void test_addition(EffectFit& f, const EffectFit* base, const Stage& s, double family) {
  const double before = base ? base->ranked_chi2() : s.chi2_0;
  f.p_value = s.p_improvement(before - f.ranked_chi2(), 1.0, f.chi2_after);
  f.p_adjusted = std::min(1.0, f.p_value * family);
  const double margin = base ? s.opt.pair_margin_bic : 0.0;
  f.significant = f.p_adjusted < s.opt.alpha && f.delta_bic < (base ? base->delta_bic : 0.0) - margin &&
                  !added_within_plausible_error(f);
}

// Where nine tenths of the fall of chi^2 from `base` to `f` lie in one quantity (as one model
// predicts it), the added cause stands in for an error in how the models predict that quantity: the
// noise model gives such a quantity a discrepancy (validation/noise_model.h), and the cause is not
// a second one.
bool rests_on_one_quantity(const Stage& s, const EffectFit& base, const EffectFit& f) {
  if (s.m.groups().size() < 2) return false;
  const auto rb = s.cost.weighted(s.m.residuals(infos_of(base), base.estimate));
  const auto rf = s.cost.weighted(s.m.residuals(infos_of(f), f.estimate));
  std::vector<double> fall(s.m.groups().size(), 0.0);
  for (std::size_t i = 0; i < rb.size(); ++i) fall[s.m.points()[i].group] += rb[i] * rb[i] - rf[i] * rf[i];
  double total = 0.0, top = 0.0;
  for (double x : fall) total += std::max(0.0, x), top = std::max(top, x);
  return total > 0.0 && top >= 0.9 * total;
}

// The change of the weighted residuals a single candidate's fit makes: the direction along which it
// can move the data.
std::vector<double> direction_of(const Stage& s, const EffectFit& single, const std::vector<double>& r0) {
  const auto kept = s.at_estimate.find(single.effects[0]);
  auto r = kept != s.at_estimate.end() && kept->second.first == single.estimate
               ? kept->second.second
               : s.cost.weighted(s.m.residuals(infos_of(single), single.estimate));
  for (std::size_t k = 0; k < r.size(); ++k) r[k] -= r0[k];
  return r;
}

// The library candidate that, fitted jointly with the causes of `base`, lowers chi^2 most. A
// first-order screen picks the ones worth a real fit: each single's direction, made orthogonal to
// the base's own directions, against the base's residuals (what the base's causes could still take
// up does not count). The family is every candidate not yet in the base.
std::optional<EffectFit> rig_wide_addition(const Stage& s, const std::vector<EffectFit>& singles, const EffectFit& base,
                                           const Progress& progress, std::vector<EffectFit>* others = nullptr) {
  const auto r0 = s.cost.weighted(s.m.residuals({}, {}));
  const auto rb = s.cost.weighted(s.m.residuals(infos_of(base), base.estimate));
  std::vector<std::vector<double>> basis;  // the base's directions, orthonormal
  std::map<std::string, const EffectFit*> single_of;
  for (const auto& f : singles) single_of[f.effects[0]] = &f;
  for (const auto& name : base.effects) {
    const auto it = single_of.find(name);
    if (it == single_of.end()) continue;
    auto d = direction_of(s, *it->second, r0);
    for (const auto& e : basis) {
      const double c = dot(d, e);
      for (std::size_t k = 0; k < d.size(); ++k) d[k] -= c * e[k];
    }
    if (const double n = std::sqrt(dot(d, d)); n > 0.0) {
      for (double& x : d) x /= n;
      basis.push_back(std::move(d));
    }
  }
  std::vector<std::pair<double, const EffectFit*>> scored;
  double family = 0.0;
  for (const auto& f : singles) {
    if (has(base, f.effects[0])) continue;
    family += 1.0;
    auto d = direction_of(s, f, r0);
    const double along = dot(rb, d);
    for (const auto& e : basis) {
      const double c = dot(d, e);
      for (std::size_t k = 0; k < d.size(); ++k) d[k] -= c * e[k];
    }
    const double dd = dot(d, d);
    // Parallel to the base: it could only move the data as the base's causes already do.
    if (!(dd > 1e-9 * dot(rb, rb) / std::max(1.0, s.n))) continue;
    scored.push_back({along * along / dd, &f});
  }
  std::stable_sort(scored.begin(), scored.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
  const auto keep = s.opt.screened_pairs > 0 ? static_cast<std::size_t>(s.opt.screened_pairs) : scored.size();
  if (scored.size() > keep) scored.resize(keep);
  std::optional<EffectFit> best;
  std::size_t tried = 0;
  for (const auto& [score_, f] : scored) {
    (void)score_;
    progress(fmt::format("{} + {}", base.label(), f->effects[0]), ++tried, scored.size());
    Fx fx = infos_of(base);
    fx.push_back(effects::find_candidate(f->effects[0]));
    std::vector<double> with_neutral = base.estimate, with_single = base.estimate;
    with_neutral.push_back(fx.back()->neutral);
    with_single.push_back(f->estimate[0]);
    FitOptions o{StrengthRange::physical, {with_neutral, with_single}};
    o.grid = false;
    EffectFit e = make_fit(fx, fit_strengths(s.cost, fx, o), s);
    if (s.m.source().has_expensive()) {
      std::vector<std::string> sig;
      for (const auto* i : fx) sig.push_back(signature_words(s.m.source().signature(*i)));
      e.signature = fmt::format("{}", fmt::join(sig, " + "));
    }
    test_addition(e, &base, s, family);
    if (rests_on_one_quantity(s, base, e)) continue;
    if (best && others) others->push_back(*best);
    if (!best || e.ranked_chi2() < best->ranked_chi2()) best = std::move(e);
    else if (others) others->back() = std::move(e);
  }
  return best;
}

// The recorded input wrong at one condition alone that, with the base's causes held, lowers chi^2
// most; then fitted jointly with them. Every record at every condition is in the family; a screen
// (each record's direction at its typical error, condition by condition, against the base's
// residuals there) picks the few worth a fit. A record whose fall rests on one reading is that
// reading's error (an outlier, named as such), not the record's: the fall without its largest
// reading must be significant too. Analytical models only: an expensive baseline would need runs of
// its own per condition and input.
std::optional<EffectFit> at_condition_addition(const Stage& s, const EffectFit* base, const Progress& progress,
                                               std::vector<EffectFit>* others = nullptr) {
  if (s.m.source().has_expensive()) return std::nullopt;
  const auto& stations = s.m.dataset().stations;
  std::vector<const effects::EffectInfo*> records;
  for (const auto& e : effects::library())
    if (e.kind == effects::EffectInfo::Kind::record && (!base || !has(*base, e.name))) records.push_back(&e);
  if (records.empty() || stations.size() < 2) return std::nullopt;
  const double family = static_cast<double>(records.size() * stations.size());
  // One wrong number per test: a condition whose record is already a cause takes no second one (two
  // records of one condition can mimic a third, a flow and a bulk density together a load cell's gain).
  std::set<std::string> taken;
  for (const auto& name : base ? base->effects : std::vector<std::string>{})
    if (const auto c = effects::split_condition(name).second; !c.empty()) taken.insert(c);
  const Fx bfx = base ? infos_of(*base) : Fx{};
  const std::vector<double> bv = base ? base->estimate : std::vector<double>{};
  const auto rb = s.cost.weighted(s.m.residuals(bfx, bv));
  std::vector<std::pair<double, std::pair<const effects::EffectInfo*, std::size_t>>> scored;
  for (const auto* e : records) {
    Fx fx = bfx;
    fx.push_back(e);
    auto v = bv;
    v.push_back(e->typical);
    auto d = s.cost.weighted(s.m.residuals(fx, v));
    for (std::size_t k = 0; k < d.size(); ++k) d[k] -= rb[k];
    std::vector<double> along(stations.size(), 0.0), dd(stations.size(), 0.0);
    for (std::size_t i = 0; i < d.size(); ++i) {
      const std::size_t c = s.m.points()[i].condition;
      along[c] += rb[i] * d[i];
      dd[c] += d[i] * d[i];
    }
    for (std::size_t c = 0; c < stations.size(); ++c)
      if (dd[c] > 0.0 && !taken.count(stations[c].condition)) scored.push_back({along[c] * along[c] / dd[c], {e, c}});
  }
  std::stable_sort(scored.begin(), scored.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
  if (scored.size() > kScreenedAtCondition) scored.resize(kScreenedAtCondition);
  struct Pick {
    const effects::EffectInfo* e = nullptr;
    Held held;
    double p = 1.0;
    double chi2 = 0.0;    // chi^2 after
    double ranked = 0.0;  // chi^2 after, the record's implausibility charged
  };
  std::optional<Pick> pick;
  std::vector<Pick> through;  // every record through the gate
  std::size_t tried = 0;
  for (const auto& [score_, which] : scored) {
    (void)score_;
    const auto [record, c] = which;
    const effects::EffectInfo* e = effects::find_candidate(record->name + "@" + stations[c].condition);
    progress(fmt::format("{} at one condition", e->name), ++tried, scored.size());
    const Cost part = s.cost.only({c});
    const Held h = fit_held(part, bfx, bv, e);
    // The fall reading by reading, and without the one that falls most.
    Fx fx = bfx;
    fx.push_back(e);
    auto v = bv;
    v.push_back(h.estimate);
    const auto before = part.weighted(part.residuals(bfx, bv)), after = part.weighted(part.residuals(fx, v));
    double drop = 0.0, largest = 0.0;
    for (std::size_t i = 0; i < before.size(); ++i) {
      const double fall = before[i] * before[i] - after[i] * after[i];
      drop += fall;
      largest = std::max(largest, fall);
    }
    const auto prior = s.prior_of(e->name);
    const double penalty = prior ? 2.0 * std::log1p(std::pow(h.estimate / prior->first, 2)) : 0.0;
    const double chi2_after = (base ? base->chi2_after : s.chi2_0) - drop;
    // The gate is the fall without its largest reading; the pick, among those through it, the fit.
    const double p = std::min(1.0, s.p_improvement(drop - largest - penalty, 1.0, chi2_after) * family);
    if (p >= s.opt.alpha) continue;
    through.push_back(Pick{e, h, p, chi2_after, chi2_after + penalty});
    if (!pick || chi2_after + penalty < pick->ranked) pick = through.back();
  }
  if (!pick || pick->p >= s.opt.alpha) return std::nullopt;
  auto joint = [&](const Pick& k) {
    Fx fx = bfx;
    fx.push_back(k.e);
    std::vector<double> start = bv;
    start.push_back(k.held.estimate);
    FitOptions o{StrengthRange::physical, {start}};
    o.grid = false;
    EffectFit f = make_fit(fx, fit_strengths(s.cost, fx, o), s);
    test_addition(f, base, s, family);
    return f;
  };
  EffectFit f = joint(*pick);
  // Another record at one condition that moves that condition's few readings about as well (a plate
  // angle and a load cell's gain there, a flow and a bulk density): the data cannot tell them apart,
  // and the verdict says so beside the one it names. So too one that fits the readings as well or
  // better and ranks lower only for the size of its error (a plate angle 12 widths off against a flow
  // 1.3 widths off): the named record is the likelier error, not the one the readings prefer.
  auto as_good = [&](double chi2, double ranked, double chi2_named, double ranked_named) {
    return ranked - ranked_named < s.opt.tie_margin_bic || chi2 - chi2_named < s.opt.tie_margin_bic;
  };
  if (others)
    for (const auto& k : through)
      if (k.e != pick->e && as_good(k.chi2, k.ranked, pick->chi2, pick->ranked))
        if (EffectFit g = joint(k); g.significant && as_good(g.chi2_after, g.ranked_chi2(), f.chi2_after, f.ranked_chi2()))
          others->push_back(std::move(g));
  return f;
}

// The explanation without its cause j, refitted from the others' strengths.
EffectFit without(const Stage& s, const EffectFit& f, std::size_t j) {
  Fx fx;
  std::vector<double> start;
  const Fx all = infos_of(f);
  for (std::size_t k = 0; k < all.size(); ++k)
    if (k != j) fx.push_back(all[k]), start.push_back(f.estimate[k]);
  FitOptions o{StrengthRange::physical, {start}};
  o.grid = false;
  return make_fit(fx, fit_strengths(s.cost, fx, o), s);
}

// A cause found early may only have stood in for later ones (a rig-wide effect taking up one
// condition's wrong record until that record was found): each earlier cause is tested again against
// the explanation without it, and dropped when it is no longer significant there, or when what it
// adds there rests on one quantity (a model-form error of that quantity, as for an added cause).
EffectFit drop_stand_ins(const Stage& s, EffectFit f, double family) {
  for (bool dropped = true; dropped && f.effects.size() > 1;) {
    dropped = false;
    for (std::size_t j = 0; j + 1 < f.effects.size(); ++j) {
      EffectFit smaller = without(s, f, j);
      if (effects::split_condition(f.effects[j]).second.empty() && rests_on_one_quantity(s, smaller, f)) {
        f = std::move(smaller);
        f.significant = true;
        f.p_adjusted = std::min(1.0, f.p_value * family);
        dropped = true;
        break;
      }
      // The test of cause j as if it were added last.
      EffectFit again = f;
      auto last = [j](auto& v) {
        std::rotate(v.begin() + static_cast<std::ptrdiff_t>(j), v.begin() + static_cast<std::ptrdiff_t>(j) + 1, v.end());
      };
      last(again.effects), last(again.parameters), last(again.estimate), last(again.uncertainty), last(again.at_bound);
      score(again, again.chi2_after, s);
      test_addition(again, &smaller, s, family);
      if (again.significant) continue;
      f = std::move(smaller);
      f.significant = true;
      f.p_adjusted = std::min(1.0, f.p_value * family);
      dropped = true;
      break;
    }
  }
  return f;
}

}  // namespace

// One strength fitted with the others held at theirs: a grid over the physical range, golden-section
// steps in the best cell, the sd from the curvature there (chi^2 rises by one at one sd).
Held fit_held(const Cost& cost, Fx fx, std::vector<double> at, const effects::EffectInfo* e) {
  fx.push_back(e);
  at.push_back(e->neutral);
  auto chi2 = [&](double x) {
    at.back() = x;
    return cost.chi2(fx, at);
  };
  constexpr int kGrid = 16;
  const double span = e->upper - e->lower;
  double best = e->neutral, best_chi2 = chi2(e->neutral);
  for (int k = 0; k <= kGrid; ++k)
    if (const double x = e->lower + span * k / kGrid, c = chi2(x); c < best_chi2) best = x, best_chi2 = c;
  double lo = std::max(e->lower, best - span / kGrid), hi = std::min(e->upper, best + span / kGrid);
  const double g = 0.5 * (std::sqrt(5.0) - 1.0);
  double x1 = hi - g * (hi - lo), x2 = lo + g * (hi - lo), c1 = chi2(x1), c2 = chi2(x2);
  for (int it = 0; it < 24; ++it) {
    if (c1 < c2) {
      hi = x2, x2 = x1, c2 = c1;
      x1 = hi - g * (hi - lo), c1 = chi2(x1);
    } else {
      lo = x1, x1 = x2, c1 = c2;
      x2 = lo + g * (hi - lo), c2 = chi2(x2);
    }
  }
  if (c1 < best_chi2) best = x1, best_chi2 = c1;
  if (c2 < best_chi2) best = x2, best_chi2 = c2;
  Held h{best, INFINITY, best_chi2};
  const double step = 1e-3 * span;
  const double curvature = (chi2(best + step) - 2.0 * best_chi2 + chi2(best - step)) / (step * step);
  if (curvature > 0.0) h.uncertainty = std::sqrt(2.0 / curvature);
  return h;
}

namespace {

// The forward search from one start (a significant single, or none: records at one condition
// first), each step's explanation in the order found.
Causes forward(const Stage& s, const std::vector<EffectFit>& singles, const EffectFit* start, const Progress& progress) {
  Causes out;
  std::optional<EffectFit> current;
  if (start) current = *start;
  std::set<std::size_t> conditions;
  for (const auto& p : s.m.points()) conditions.insert(p.condition);
  // A cause per strength the data can carry: fewer conditions than causes plus two cannot tell them apart.
  const std::size_t most = std::clamp<std::size_t>(conditions.size() >= 2 ? conditions.size() - 2 : 0, 1, kMaxCauses);
  // Each step adds a cause and may drop one that stood in for it: a bounded number of steps, so that
  // two candidates that trade places cannot keep the search going.
  for (std::size_t step = 0; step < 2 * kMaxCauses + 2; ++step) {
    const std::size_t k = current ? current->effects.size() : 0;
    if (k >= most) break;
    std::optional<EffectFit> next;
    std::vector<EffectFit> others;
    if (current) next = rig_wide_addition(s, singles, *current, progress, &others);
    std::vector<EffectFit> at_others;
    if (auto one = at_condition_addition(s, current ? &*current : nullptr, progress, &at_others);
        one && one->significant && (!next || !next->significant || one->p_adjusted < next->p_adjusted)) {
      if (next) others.push_back(std::move(*next));
      next = std::move(one);
    }
    for (auto& o : at_others) others.push_back(std::move(o));
    if (!next) break;
    if (!next->significant) {
      out.next = std::move(next);
      break;
    }
    const std::size_t before = next->effects.size();
    EffectFit kept = drop_stand_ins(s, std::move(*next), static_cast<double>(singles.size()));
    // An earlier cause was a stand-in: the explanations found on the way no longer lead here.
    if (kept.effects.size() < before) out.chosen.clear();
    out.alternatives.clear();
    for (auto& o : others)
      if (o.significant && o.chi2_after - kept.chi2_after < s.opt.tie_margin_bic && o.effects.size() == kept.effects.size())
        out.alternatives.push_back(std::move(o));
    current = kept;
    out.chosen.push_back(std::move(kept));
  }
  return out;
}

// The significant singles the search starts from: the leader, and the next few that may be named
// (a greedy search from the leader alone misses a pair whose first cause ranks second as a single:
// a belt speed record mimicking a drag that, with the plate's record, explains everything).
constexpr std::size_t kStarts = 3;

}  // namespace

double bic_of(const EffectFit& f, const Stage& s) {
  return f.ranked_chi2() + static_cast<double>(f.effects.size()) * std::log(std::max(s.n, 2.0));
}

std::vector<EffectFit> records_for_reading(const Stage& s, const EffectFit* best, std::size_t i) {
  const Misfit& m = s.m;
  if (m.source().has_expensive() || i >= m.size() || !s.nm.excluded[i]) return {};
  const std::size_t c = m.points()[i].condition;
  const std::string& condition = m.dataset().stations[c].condition;
  NoiseModel back = s.nm;
  back.excluded[i] = 0;
  const auto w = back.weights(m);
  const Cost part = Cost(m, w).only({c});
  const auto n_all = static_cast<double>(std::count_if(w.begin(), w.end(), [](double x) { return x > 0.0; }));
  // The limit the outlier test left the reading out by (validation/noise_model.cpp, find_outlier).
  const double limit = gsl_cdf_ugaussian_Qinv(s.opt.alpha / (2.0 * n_all));
  const Fx bfx = best ? infos_of(*best) : Fx{};
  const std::vector<double> bv = best ? best->estimate : std::vector<double>{};
  std::vector<EffectFit> out;
  for (const auto& lib : effects::library()) {
    if (lib.kind != effects::EffectInfo::Kind::record) continue;
    const effects::EffectInfo* e = effects::find_candidate(lib.name + "@" + condition);
    if (!e || (best && (has(*best, e->name) || has(*best, lib.name)))) continue;
    const Held h = fit_held(part, bfx, bv, e);
    // At an edge of its range the record does not reach the reading: it only leans towards it.
    const double span = e->upper - e->lower;
    if (!std::isfinite(h.uncertainty) || h.estimate <= e->lower + 1e-3 * span || h.estimate >= e->upper - 1e-3 * span)
      continue;
    Fx fx = bfx;
    fx.push_back(e);
    auto v = bv;
    v.push_back(h.estimate);
    // h.chi2: the fit's chi^2 over the condition's readings (`part`), the reading back in.
    const double n = static_cast<double>(part.size());
    if (n < 2 || std::abs(m.residuals(fx, v)[i] * w[i]) > limit || gsl_cdf_chisq_Q(h.chi2, n - 1) < s.opt.alpha)
      continue;
    EffectFit f;
    f.effects = {e->name};
    f.parameters = {e->parameter};
    f.estimate = {h.estimate};
    f.uncertainty = {h.uncertainty};
    f.at_bound = {false};
    score(f, h.chi2, s);  // chi2_after here: the condition's readings alone
    out.push_back(std::move(f));
  }
  std::stable_sort(out.begin(), out.end(), [](const EffectFit& a, const EffectFit& b) { return a.ranked_chi2() < b.ranked_chi2(); });
  std::erase_if(out, [&](const EffectFit& f) { return f.ranked_chi2() - out.front().ranked_chi2() >= s.opt.tie_margin_bic; });
  return out;
}

Causes more_causes(const Stage& s, const std::vector<EffectFit>& singles, const EffectFit* top,
                   const Progress& progress, int jobs) {
  std::vector<const EffectFit*> starts = {top};
  if (top)
    for (const auto& f : singles)
      if (starts.size() < kStarts && &f != top && f.significant && f.beaten_outside_range_by.empty()) starts.push_back(&f);
  Causes out;
  const EffectFit* from = top;
  double best_bic = INFINITY;
  for (const EffectFit* start : starts) {
    Causes c = forward(s, singles, start, progress);
    const EffectFit* last = !c.chosen.empty() ? &c.chosen.back() : start;
    const double bic = last ? bic_of(*last, s) : s.chi2_0;
    // Another start wins only where it ends clearly better than the leader's search: by the margin a
    // further cause needs over the explanation it adds to.
    if (start == top ? bic < best_bic : bic < best_bic - s.opt.pair_margin_bic) {
      if (start != top && !c.chosen.empty()) c.alternatives.clear();
      out = std::move(c);
      from = start;
      best_bic = bic;
    }
  }
  const EffectFit* top_start = from;
  // An expensive baseline's verdict on its largest explanation: its real runs at the fitted strengths
  // must still beat the explanation one cause smaller by the same tests, or it is not kept.
  while (!out.chosen.empty() && jobs > 0 && s.m.source().reruns_expensive()) {
    EffectFit& f = out.chosen.back();
    const Fx fx = infos_of(f);
    for (std::size_t i = 0; i < f.estimate.size(); ++i) f.estimate[i] = on_grid(f.estimate[i], f.uncertainty[i]);
    s.m.source().prepare_exact(fx, f.estimate, jobs,
                               fmt::format("the explanation by {} causes, run for real before it is kept", fx.size()));
    rescore(f, s.cost.chi2_of(s.m.residuals_exact(fx, f.estimate)), s);
    const EffectFit* smaller = out.chosen.size() >= 2 ? &out.chosen[out.chosen.size() - 2] : top_start;
    test_addition(f, smaller, s, static_cast<double>(singles.size()));
    if (f.significant) break;
    out.chosen.pop_back();
  }
  std::reverse(out.chosen.begin(), out.chosen.end());
  return out;
}

}  // namespace chutelab::validation::detail
