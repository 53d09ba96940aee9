// The diagnosis's search under one noise model and the rounds that settle that model: every single
// candidate fitted and judged, the leaders run for real, fits outside a range, the further causes
// (validation/diagnosis_causes.cpp), and the noise model re-assessed on what the explanation leaves.
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

const EffectFit* leader(const std::vector<EffectFit>& singles) {
  return !singles.empty() && singles.front().significant ? &singles.front() : nullptr;
}

std::vector<double> residuals_at(const Misfit& m, const EffectFit* f) {
  if (!f) return m.residuals({}, {});
  return m.residuals(infos_of(*f), f->estimate);
}

namespace {

// Every single candidate fitted inside its physical range, judged (Bonferroni over the candidates)
// and ranked by chi^2.
std::vector<EffectFit> fit_singles(const Stage& s, const Progress& progress) {
  const auto& lib = effects::library();
  std::vector<EffectFit> out;
  for (const auto& e : lib) {
    progress(e.name, static_cast<std::size_t>(&e - lib.data()) + 1, lib.size());
    const Fx fx = {&e};
    StrengthFit fit = fit_strengths(s.cost, fx);
    if (!fit.residuals.empty()) s.at_estimate[e.name] = {fit.estimate, std::move(fit.residuals)};
    EffectFit f = make_fit(fx, fit, s);
    if (s.m.source().has_expensive()) f.signature = signature_words(s.m.source().signature(e));
    out.push_back(std::move(f));
  }
  return out;
}

void judge_singles(std::vector<EffectFit>& singles, const Stage& s) {
  const double k = static_cast<double>(singles.size());
  for (auto& f : singles) {
    f.p_adjusted = std::min(1.0, f.p_value * k);
    // A record fitted within its plausible error is not a wrong record, however small its noise: a
    // rig that agrees with the data once an input moves by less than its own tolerance needs no
    // correction (another code's model-form differences find such stand-ins).
    f.significant = f.p_adjusted < s.opt.alpha && !f.within_plausible_error();
  }
  std::stable_sort(singles.begin(), singles.end(), [](const auto& a, const auto& b) { return a.ranked_chi2() < b.ranked_chi2(); });
  for (std::size_t i = 0; i < singles.size(); ++i) singles[i].rank = static_cast<int>(i) + 1;
}

// An expensive model that runs with effects ranks by signatures, which are differences carried
// along a response: close to the data they can misorder candidates whose real runs differ. So the
// leading significant candidates are run for real at their fitted strengths, and the ranking is
// the runs'. Nothing is run when nothing is significant.
void confirm_leaders(std::vector<EffectFit>& singles, const Stage& s, int jobs) {
  int confirmed = 0;
  for (auto& f : singles) {
    if (confirmed >= s.opt.confirm || !f.significant) break;
    const Fx fx = infos_of(f);
    // A measurement effect acts on the expensive model's output exactly: a run would add nothing.
    if (s.m.source().signature(*fx[0]) == PredictionSource::Signature::none) continue;
    f.estimate[0] = on_grid(f.estimate[0], f.uncertainty[0]);
    s.m.source().prepare_exact(fx, f.estimate, jobs,
                               fmt::format("leading candidate {}, run for real to confirm its rank", confirmed + 1));
    rescore(f, s.cost.chi2_of(s.m.residuals_exact(fx, f.estimate)), s);
    ++confirmed;
  }
  judge_singles(singles, s);
}

// A single at an edge of its physical range refitted over its extended range, when the misfit
// falls past the edge: what the data want whatever physics allows.
void fit_outside(std::vector<EffectFit>& singles, const Stage& s) {
  const double limit = s.opt.alpha / static_cast<double>(singles.size());
  for (auto& f : singles) {
    if (f.at_bound.empty() || !f.at_bound[0]) continue;
    const auto* e = effects::find_candidate(f.effects[0]);
    const double span = e->upper - e->lower;
    const bool low = f.estimate[0] <= e->lower + 1e-3 * span;
    const double past = low ? e->lower - 0.05 * span : e->upper + 0.05 * span;
    const Fx fx = {e};
    const double at_edge = f.chi2_from_signatures ? *f.chi2_from_signatures : f.chi2_after;
    if (s.cost.chi2(fx, std::vector<double>{past}) >= at_edge) continue;
    const auto u = fit_strengths(s.cost, fx, {StrengthRange::extended, {{past}}});
    UnboundedFit ub{u.estimate[0], u.uncertainty[0], u.chi2, false};
    const double sd = std::isfinite(ub.uncertainty) ? ub.uncertainty : 0.0;
    const bool outside = ub.estimate + 2.0 * sd < e->lower || ub.estimate - 2.0 * sd > e->upper;
    ub.wants_outside = outside && s.p_improvement(at_edge - ub.chi2, 1.0, ub.chi2) < limit;
    f.unbounded = ub;
  }
}

// The candidate whose fit outside its range explains the data best, if any wants to go there.
const EffectFit* best_outside(const std::vector<EffectFit>& singles) {
  const EffectFit* best = nullptr;
  for (const auto& f : singles)
    if (f.unbounded && f.unbounded->wants_outside && (!best || f.unbounded->chi2 < best->unbounded->chi2)) best = &f;
  return best;
}

// An in-range explanation may not be named when a fit outside the range explains the data clearly
// better: that candidate was clipped, and a mimic would take its place.
void veto_by_outside(std::vector<EffectFit>& fits, const EffectFit* outside, const Stage& s) {
  if (!outside) return;
  const double ln_n = std::log(std::max(s.n, 2.0));
  const double bic_out = outside->unbounded->chi2 + ln_n;
  // Only the leader is at stake (the list is ranked; the others could not be named anyway).
  for (auto& f : fits) {
    const double bic = f.ranked_chi2() + static_cast<double>(f.effects.size()) * ln_n;
    if (bic_out < bic - s.opt.tie_margin_bic) f.beaten_outside_range_by = outside->effects[0];
    break;
  }
}

}  // namespace

Explanations explain(const Stage& s, const Progress& progress, int jobs, bool confirm) {
  Explanations x;
  x.singles = fit_singles(s, progress);
  judge_singles(x.singles, s);
  if (confirm && s.m.source().reruns_expensive()) confirm_leaders(x.singles, s, jobs);
  fit_outside(x.singles, s);
  x.outside = best_outside(x.singles);
  veto_by_outside(x.singles, x.outside, s);
  const double ln_n = std::log(std::max(s.n, 2.0));
  double bic = INFINITY;
  auto consider = [&](const Fx& fx, const std::vector<double>& v, double chi2) {
    if (chi2 + static_cast<double>(fx.size()) * ln_n >= bic) return;
    bic = chi2 + static_cast<double>(fx.size()) * ln_n;
    x.fx = fx, x.strengths = v, x.chi2 = chi2, x.any = true;
  };
  const EffectFit* top = leader(x.singles);
  if (top && !top->beaten_outside_range_by.empty()) top = nullptr;
  if (top) consider(infos_of(*top), top->estimate, top->chi2_after);
  if (x.outside) consider(infos_of(*x.outside), {x.outside->unbounded->estimate}, x.outside->unbounded->chi2);
  std::optional<EffectFit> next;
  // Also where only a fit outside a range leads: a record wrong at one condition can move the data
  // far more than any rig-wide candidate, whose best fit then leaves its range to take what it can;
  // the explanation with the lower BIC leads either way.
  if (s.opt.pairs) {
    Causes c = more_causes(s, x.singles, top, progress, confirm ? jobs : 0);
    x.pairs = std::move(c.chosen);
    next = std::move(c.next);
    x.alternatives = std::move(c.alternatives);
    veto_by_outside(x.pairs, x.outside, s);
    std::erase_if(x.pairs, [](const EffectFit& f) { return !f.beaten_outside_range_by.empty(); });
    // Found from nothing beside a fit outside a range, the causes must beat that fit as a further
    // cause beats the explanation it adds to: they spend more strengths on what one out-of-range
    // candidate may explain alone (a wrong-sign drag taken up by a belt speed record at its fastest
    // condition and a rig-wide one).
    if (!top && x.outside && !x.pairs.empty() &&
        !(bic_of(x.pairs.front(), s) < x.outside->unbounded->chi2 + ln_n - s.opt.pair_margin_bic))
      x.pairs.clear(), next.reset(), x.alternatives.clear();
    if (!x.pairs.empty()) consider(infos_of(x.pairs.front()), x.pairs.front().estimate, x.pairs.front().chi2_after);
  }
  x.full_fx = x.fx, x.full_strengths = x.strengths;
  const std::size_t chosen = x.pairs.empty() ? (top ? 1 : 0) : x.pairs.front().effects.size();
  if (next && x.any && next->effects.size() == chosen + 1 && std::equal(x.fx.begin(), x.fx.end(), infos_of(*next).begin())) {
    x.full_fx = infos_of(*next);
    x.full_strengths = next->estimate;
    x.next = std::move(next);
  }
  return x;
}

Settled settle(const Misfit& m, const DiagnoseOptions& opt, const Progress& progress) {
  Settled out;
  out.nm = NoiseModel::stated(m);
  std::set<std::string> measured;
  for (const auto& g : m.groups()) measured.insert(g.quantity);
  const std::size_t quantities = measured.size();
  const int max_rounds = 4 + 2 * static_cast<int>(opt.max_outlier_share * static_cast<double>(m.size()));
  std::set<std::size_t> readmitted;
  for (out.rounds = 1; out.rounds <= max_rounds; ++out.rounds) {
    const Stage s(m, opt, out.nm);
    Progress shown = progress;
    shown.round = out.rounds;
    Explanations x = explain(s, shown, 0, false);
    const auto r = x.any ? m.residuals(x.fx, x.strengths) : m.residuals({}, {});
    if (const auto o = find_outlier(m, out.nm, r, opt.alpha, opt.max_outlier_share)) {
      out.nm.excluded[*o] = 1;
      continue;
    }
    if (const auto back = find_readmitted(m, out.nm, r, opt.alpha); back && !readmitted.count(*back)) {
      out.nm.excluded[*back] = 0;
      readmitted.insert(*back);  // once: a reading may not go in and out for ever
      continue;
    }
    // An effect that fixes one quantity at the expense of the others (where others are measured):
    // an error in how the models predict that quantity is the simpler reading, so it gets a
    // discrepancy and the fits are repeated.
    // The leading single is asked first: further causes can hide its cost in the other quantities
    // (a plate friction that fixes R_s, with a plate angle to undo what it does to V_a).
    const EffectFit* top = leader(x.singles);
    std::optional<Evidence> e;
    if (x.any && quantities >= 2 && top && top->beaten_outside_range_by.empty())
      e = concentrated(s, infos_of(*top), top->estimate);
    if (x.any && quantities >= 2 && !(e && out.nm.discrepancy[e->group] == 0.0)) e = concentrated(s, x.fx, x.strengths);
    if (e && out.nm.discrepancy[e->group] == 0.0) {
      const double tau = discrepancy_for(m, m.groups()[e->group], e->before, out.nm.excluded, out.nm.scale);
      if (tau > 0.0) {
        out.nm.discrepancy[e->group] = tau;
        continue;
      }
    }
    // The noise model is judged on what the explanation and the best further cause leave: scatter
    // that a candidate's signature takes up is structure, not noise, whether it was named or not.
    const auto full = x.full_fx.size() > x.fx.size() ? m.residuals(x.full_fx, x.full_strengths) : r;
    NoiseModel next = assess_noise(m, out.nm, full, static_cast<int>(x.full_fx.size()), opt.alpha, &out.scale);
    if (next.settled_with(out.nm)) {
      out.settled = true;
      out.last = std::move(x);
      return out;
    }
    out.nm = std::move(next);
  }
  out.rounds = max_rounds;
  return out;
}

}  // namespace detail
}  // namespace chutelab::validation
