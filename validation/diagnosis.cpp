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

std::string EffectFit::label() const { return fmt::format("{}", fmt::join(effects, " + ")); }

bool EffectFit::is_record() const {
  for (const auto& n : effects)
    if (const auto* e = effects::find_candidate(n); !e || e->kind != effects::EffectInfo::Kind::record) return false;
  return !effects.empty();
}

bool EffectFit::within_plausible_error() const {
  if (!is_record() || prior_width.size() != estimate.size()) return false;
  for (std::size_t i = 0; i < estimate.size(); ++i)
    if (!(prior_width[i] > 0.0) || !(std::abs(estimate[i]) < prior_width[i])) return false;
  return true;
}

const EffectFit* DiagnosisResult::best() const {
  if (!any_significant) return nullptr;
  const EffectFit* b = !pairs.empty() ? &pairs.front() : singles.empty() ? nullptr : &singles.front();
  return b && b->beaten_outside_range_by.empty() ? b : nullptr;
}

void check(const DiagnoseOptions& o) {
  auto need = [](bool ok, const char* field, const std::string& what) {
    if (!ok) throw InputError("", 0, field, what);
  };
  need(o.alpha > 0.0 && o.alpha <= 0.5, "alpha", fmt::format("must lie in (0, 0.5], got {}", o.alpha));
  need(std::isfinite(o.pair_margin_bic) && o.pair_margin_bic >= 0.0, "pair_margin_bic",
       fmt::format("must be finite and >= 0, got {}", o.pair_margin_bic));
  need(std::isfinite(o.tie_margin_bic) && o.tie_margin_bic >= 0.0, "tie_margin_bic",
       fmt::format("must be finite and >= 0, got {}", o.tie_margin_bic));
  need(o.proportional_cosine > 0.0 && o.proportional_cosine <= 1.0, "proportional_cosine",
       fmt::format("must lie in (0, 1], got {}", o.proportional_cosine));
  need(o.max_outlier_share >= 0.0 && o.max_outlier_share <= 0.5, "max_outlier_share",
       fmt::format("must lie in [0, 0.5], got {}", o.max_outlier_share));
  need(o.jobs >= 0 && o.jobs <= 4096, "jobs", fmt::format("must lie in [0, 4096], got {}", o.jobs));
  need(o.confirm >= 0 && o.confirm <= 64, "confirm", fmt::format("must lie in [0, 64], got {}", o.confirm));
  need(o.screened_pairs >= 0 && o.screened_pairs <= 10000, "screened_pairs",
       fmt::format("must lie in [0, 10000], got {}", o.screened_pairs));
  need(o.profile_runs == 0 || (o.profile_runs >= 3 && o.profile_runs <= 12), "profile_runs",
       fmt::format("must be 0 or lie in [3, 12], got {}", o.profile_runs));
}

namespace detail {

Fx infos_of(const EffectFit& f) {
  Fx v;
  for (const auto& n : f.effects) v.push_back(effects::find_candidate(n));
  return v;
}

namespace {

// How far a recorded input is plausibly off, in its candidate's unit: the dataset's stated
// uncertainty of that input (the median over the conditions that state it), else the input's
// documented default (effects/registry.h, EffectInfo::prior_width).
std::pair<double, bool> record_width(const Dataset& d, const effects::EffectInfo& e) {
  std::vector<double> w;
  for (std::size_t c = 0; c < d.stations.size() && c < d.input_uncertainty.size() && e.width_in_unit; ++c) {
    const InputUncertainties& iu = d.input_uncertainty[c];
    std::optional<double> u = e.input == "belt_speed"         ? iu.belt_speed
                              : e.input == "mass_flow"        ? iu.mass_flow
                              : e.input == "plate_distance"   ? iu.plate_distance
                              : e.input == "plate_top"        ? iu.plate_top
                              : e.input == "stream_thickness" ? iu.stream_thickness
                                                              : std::nullopt;
    for (const auto& [field, value] : iu.rig)
      if (fmt::format("{}.{}", field->section, field->key) == e.input) u = value;
    if (u && *u > 0.0) {
      const double x = e.width_in_unit(d.stations[c], *u);
      if (std::isfinite(x) && x > 0.0) w.push_back(x);
    }
  }
  if (w.empty()) return {e.prior_width, false};
  std::nth_element(w.begin(), w.begin() + static_cast<std::ptrdiff_t>(w.size() / 2), w.end());
  return {w[w.size() / 2], true};
}

}  // namespace

Stage::Stage(const Misfit& misfit, const DiagnoseOptions& o, NoiseModel noise)
    : m(misfit), opt(o), nm(std::move(noise)), cost(misfit, nm.weights(misfit)) {
  chi2_0 = cost.chi2({}, {});
  n = static_cast<double>(cost.size());
  candidates = effects::library().size();
  for (const auto& e : effects::library())
    if (e.kind == effects::EffectInfo::Kind::record) prior[e.name] = record_width(misfit.dataset(), e);
}

double Stage::p_improvement(double drop, double k, double after) const {
  drop = std::max(0.0, drop);
  if (nm.scale > 1.0) return gsl_cdf_fdist_Q((drop / k) / std::max(after / dof(k), 1e-300), k, dof(k));
  return gsl_cdf_chisq_Q(drop, k);
}

std::optional<std::pair<double, bool>> Stage::prior_of(const std::string& candidate) const {
  const auto it = prior.find(effects::split_condition(candidate).first);
  if (it == prior.end()) return std::nullopt;
  return it->second;
}

void score(EffectFit& e, double chi2, const Stage& s) {
  const double k = static_cast<double>(e.effects.size());
  e.chi2_before = s.chi2_0;
  e.chi2_after = chi2;
  e.prior_width.assign(e.effects.size(), 0.0);
  e.prior_stated.assign(e.effects.size(), false);
  e.prior_penalty = 0.0;
  for (std::size_t i = 0; i < e.effects.size(); ++i)
    if (const auto prior = s.prior_of(e.effects[i])) {
      const auto [w, stated] = *prior;
      e.prior_width[i] = w;
      e.prior_stated[i] = stated;
      e.prior_penalty += 2.0 * std::log1p(std::pow(e.estimate[i] / w, 2));
    }
  e.delta_bic = (chi2 + e.prior_penalty + k * std::log(std::max(s.n, 2.0))) - s.chi2_0;
  // The misfit beyond noise: what is left counts as noise up to its degrees of freedom.
  const double floor = std::min(chi2, s.dof(k));
  e.explained_fraction = s.chi2_0 - floor > 0.0 ? std::clamp((s.chi2_0 - chi2) / (s.chi2_0 - floor), 0.0, 1.0) : 0.0;
  e.p_value = s.p_improvement(s.chi2_0 - chi2 - e.prior_penalty, k, chi2);
}

EffectFit make_fit(const Fx& fx, const StrengthFit& f, const Stage& s) {
  EffectFit e;
  for (const auto* i : fx) {
    e.effects.push_back(i->name);
    e.parameters.push_back(i->unit.empty() ? i->parameter : fmt::format("{}_{}", i->parameter, i->unit));
  }
  e.estimate = f.estimate;
  e.uncertainty = f.uncertainty;
  e.status = f.status;
  e.at_bound = f.at_bound;
  score(e, f.chi2, s);
  return e;
}

void rescore(EffectFit& e, double chi2, const Stage& s) {
  if (!e.chi2_from_signatures) e.chi2_from_signatures = e.chi2_after;
  score(e, chi2, s);
}

std::string signature_words(PredictionSource::Signature s) {
  switch (s) {
    case PredictionSource::Signature::own_runs: return "own runs";
    case PredictionSource::Signature::cheap_models: return "analytical only";
    case PredictionSource::Signature::none: return "exact (measurement)";
  }
  return "";
}

// Through core/progress.h like every command's progress: --quiet silences it, a terminal sees one
// line rewritten per fit, a log a line per pass over the candidates.
void Progress::operator()(const std::string& what, std::size_t k, std::size_t of) const {
  if (!on) return;
  const std::chrono::duration<double> spent = std::chrono::steady_clock::now() - started;
  const std::string pass = round > 1 ? fmt::format("round {} of the noise model: ", round) : "";
  if (k == 1)
    progress::line(fmt::format("diagnose: {}fitting {} candidates ({:.0f} s so far)", pass, of, spent.count()));
  progress::status(fmt::format("diagnose: {}fitting {} ({}/{}, {:.0f} s so far)", pass, what, k, of, spent.count()));
  if (k == of) progress::status("");
}

}  // namespace detail

namespace {

using namespace detail;

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

const EffectFit* leader(const std::vector<EffectFit>& singles) {
  return !singles.empty() && singles.front().significant ? &singles.front() : nullptr;
}

std::vector<double> residuals_at(const Misfit& m, const EffectFit* f) {
  if (!f) return m.residuals({}, {});
  return m.residuals(infos_of(*f), f->estimate);
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

}  // namespace detail

namespace {

}  // namespace

namespace detail {

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

}  // namespace detail

namespace {

// The explanations under one noise model: every single inside its range, those at an edge also
// outside it, and every further cause the data support (validation/diagnosis_causes.cpp).
struct Explanations {
  std::vector<EffectFit> singles, pairs;  // pairs: explanations by more causes than the best single, largest first
  const EffectFit* outside = nullptr;  // in singles: the best fit outside a range that the data want
  // The leading explanation (lowest BIC among the significant ones, a fit outside a range included).
  Fx fx;
  std::vector<double> strengths;
  double chi2 = 0.0;
  bool any = false;
  // The leading explanation with the best further cause, significant or not: the noise model is
  // judged on what it leaves, so that it takes only scatter that no candidate explains.
  Fx full_fx;
  std::vector<double> full_strengths;
  std::optional<EffectFit> next;  // that further cause's explanation
  std::vector<EffectFit> alternatives;  // about as good in the last cause's place (Causes::alternatives)
};

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

// The explanations and the noise model that agree with each other: explain, take the leading
// explanation's residuals, leave out one outlier or re-assess the noise, until nothing changes.
struct Settled {
  NoiseModel nm;
  ScaleEstimate scale;
  int rounds = 0;
  bool settled = false;
  // The explanations fitted under the settled noise model, in its last round.
  std::optional<Explanations> last;
};

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

double weight_without_exclusion(const NoiseModel& nm, const Misfit& m, std::size_t i) {
  const auto& p = m.points()[i];
  return 1.0 / std::sqrt(nm.scale * nm.scale + std::pow(nm.discrepancy[p.group] / p.uncertainty, 2));
}

double to_boundary(const MisfitPoint& p) { return p.q ? info(*p.q).to_boundary : 1e3; }

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
                                     const std::vector<double>& exact = {}, const std::string& only = "") {
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

}  // namespace

namespace detail {

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

}  // namespace detail

namespace {

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
      const bool tie = named.size() == 1 && f.chi2_after - top->chi2_after < s.opt.tie_margin_bic;
      // Proportional: the data cannot tell them apart, whatever the ranking.
      const bool proportional = std::abs(cosine(d_top, fitted_change(s.m, f, r0))) >= s.opt.proportional_cosine &&
                                f.chi2_after - top->chi2_after <= std::max(4.0, 0.05 * top->chi2_after);
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

Verdict verdict_of(const DiagnosisResult& out, const EffectFit* best, const EffectFit* outside) {
  if (out.n_data == 0) return Verdict::no_data;
  if (best) {
    bool edge = false;
    for (bool b : best->at_bound) edge = edge || b;
    return out.goodness_of_fit && !edge && out.shape.empty() ? Verdict::missing_effect : Verdict::partial_explanation;
  }
  if (outside) return Verdict::out_of_range;
  // The scale, where applied, accounts for scatter without structure; outliers are left out.
  return !out.leftovers.empty() || !out.model_form.empty() ? Verdict::outside_library : Verdict::consistent;
}

int jobs_of(const DiagnoseOptions& opt) {
  return opt.jobs > 0 ? opt.jobs : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
}

}  // namespace

DiagnosisResult diagnose(const Dataset& d, const std::vector<ModelPtr>& models, const DiagnoseOptions& opt) {
  check(opt);
  DiagnosisResult out;
  out.dataset = d.setup.name.empty() ? d.dir.filename().string() : d.setup.name;
  for (const auto& m : models) out.models.push_back(m->name());
  const int jobs = jobs_of(opt);
  // Every MPI rank fits the same candidates (their results must agree on every rank), so the
  // threads of one rank are its share of the cores.
  const Misfit m(std::make_shared<const PredictionSource>(d, models, opt.fixed,
                                                          std::max(1, jobs / campaign::ranks())));
  out.n_data = static_cast<int>(m.size());
  out.n_without_uncertainty = m.left_out();
  std::set<std::size_t> conditions;
  std::set<std::string> quantities;
  for (const auto& p : m.points()) conditions.insert(p.condition), quantities.insert(p.quantity);
  out.n_conditions = static_cast<int>(conditions.size());
  out.n_quantities = static_cast<int>(quantities.size());
  const auto r0 = m.residuals({}, {});
  for (double x : r0) out.chi2_baseline += x * x;
  out.baseline_p_value = m.size() ? gsl_cdf_chisq_Q(out.chi2_baseline, static_cast<double>(m.size())) : 1.0;
  out.patterns = residual_patterns(m, r0);
  out.used_surrogate = m.source().has_expensive();
  for (const auto& mm : models)
    if (mm->expensive() && !mm->runs_with_effects()) out.exported_models.emplace_back(mm->name(), mm->description());
  if (m.source().has_expensive()) {
    const Predictions base = m.source().predict({}, {});
    for (std::size_t c = 0; c < base.size(); ++c)
      for (const auto& p : base[c])
        if (!p.unsteady.empty())
          out.unsteady_baseline.push_back(fmt::format("{} ({})", m.dataset().stations[c].condition, fmt::join(p.unsteady, ", ")));
  }
  if (m.size() == 0) {
    out.verdict_code = Verdict::no_data;
    describe(out, opt);
    return out;
  }
  if (m.source().has_expensive()) {
    // An expensive baseline's own response to every candidate it can represent: one probe run per
    // candidate and condition, side by side (they are independent).
    Fx all;
    for (const auto& e : effects::library()) all.push_back(&e);
    m.source().prepare_signatures(all, jobs);
  }
  Progress progress{opt.progress && d.stations.size() >= 500};
  const Drivers drivers = drivers_of(m);
  Settled settled = settle(m, opt, progress);
  const Stage s(m, opt, settled.nm);
  out.noise_rounds = settled.rounds;
  // Without an expensive model to re-run, the final fits are the settled round's: the same stage,
  // and nothing to confirm (a third of a diagnosis that settles in two rounds).
  Explanations x = settled.last && !m.source().reruns_expensive() ? std::move(*settled.last)
                                                                   : explain(s, Progress{}, jobs, true);
  out.singles = std::move(x.singles);
  out.pairs = std::move(x.pairs);
  out.next_cause = std::move(x.next);
  const std::vector<EffectFit> x_alternatives = std::move(x.alternatives);
  const EffectFit* outside = nullptr;
  for (const auto& f : out.singles)
    if (f.unbounded && f.unbounded->wants_outside) {
      out.wants_outside.push_back(f.effects[0]);
      if (!outside || f.unbounded->chi2 < outside->unbounded->chi2) outside = &f;
    }
  out.any_significant = leader(out.singles) != nullptr || !out.pairs.empty();
  EffectFit* best = const_cast<EffectFit*>(out.best());
  if (best && best->effects.size() == 1 && m.source().reruns_expensive() && opt.profile_runs > 0) {
    profile_best(*best, s, jobs);
    // The real runs may move a record inside its plausible error: then it is not named.
    if (best->within_plausible_error()) {
      best->significant = false;
      out.any_significant = false;
      best = nullptr;
    }
  }
  if (best) {
    out.leftovers = leftovers_of(s, best_residuals(s, best), static_cast<double>(best->effects.size()),
                                 best->chi2_after, drivers);
    out.goodness_of_fit = out.leftovers.empty();
    out.influential = influential(s, *best);
    if (const auto e = concentrated(s, infos_of(*best), best->estimate)) {
      const auto& g = m.groups()[e->group];
      out.concentrated = Concentration{best->effects[e->effect], g.quantity, m.models()[g.model]->name(), e->share};
    }
    if (best->profile && !best->profile->points.empty()) {
      // Its real runs are the profile's points.
      out.confirmed_chi2 = best->profile->lowest()->second;
    } else if (m.source().reruns_expensive()) {
      const Fx fx = infos_of(*best);
      m.source().prepare_exact(fx, best->estimate, jobs, "the recommended explanation, run for real");
      out.confirmed_chi2 = s.cost.chi2_of(m.residuals_exact(fx, best->estimate));
    }
  } else if (!outside) {
    out.leftovers = leftovers_of(s, r0, 0.0, s.chi2_0, drivers);
    out.goodness_of_fit = out.leftovers.empty();
  }
  if (best && best->chi2_from_signatures && m.source().reruns_expensive())
    out.shifts = shifts_of(s, infos_of(*best), best->estimate, best_residuals(s, best));
  else if (best) out.shifts = shifts_of(s, infos_of(*best), best->estimate);
  else if (outside) out.shifts = shifts_of(s, infos_of(*outside), {outside->unbounded->estimate});
  else out.shifts = shifts_of(s, {}, {});
  // A record wrong at one condition: its words speak of that condition's readings, which the mean
  // over every condition would dilute eight-fold on the reference rig.
  if (best) {
    std::set<std::string> at;
    for (const auto& e : best->effects) at.insert(effects::split_condition(e).second);
    if (at.size() == 1 && !at.begin()->empty()) {
      out.shifts_condition = *at.begin();
      out.shifts_there = best->chi2_from_signatures && m.source().reruns_expensive()
                             ? shifts_of(s, infos_of(*best), best->estimate, best_residuals(s, best), out.shifts_condition)
                             : shifts_of(s, infos_of(*best), best->estimate, {}, out.shifts_condition);
    }
  }
  out.model_form = model_form_of(s, out.shifts);
  fill_leftovers(out.leftovers, out.shifts);
  out.outliers = name_outliers(s, best, out.singles);
  out.alpha = opt.alpha;
  for (std::size_t i = 0; i < m.size(); ++i)
    if (!s.nm.excluded[i]) out.chi2_kept += r0[i] * r0[i], ++out.n_kept;
  out.kept_p_value = out.n_kept ? gsl_cdf_chisq_Q(out.chi2_kept, static_cast<double>(out.n_kept)) : 1.0;
  out.scale = {settled.scale.factor, settled.scale.dof, settled.scale.p_high, settled.scale.p_low,
               s.nm.scale > 1.0, settled.scale.p_low < opt.alpha};
  if (out.best()) ties_of(out, s, r0);
  // Another cause in the last place of an explanation by several that fits about as well.
  if (const EffectFit* b = out.best(); b && !out.pairs.empty() && b == &out.pairs.front())
    for (const auto& alt : x_alternatives) {
      out.indistinguishable.push_back(alt.label());
      auto d = discriminators(m, *b, alt, false);
      if (d.empty()) d.push_back({b->label(), alt.label(), "", "", "", "", 0, 0, 0, false});
      out.ties.push_back(d.front());
    }
  out.thin_data = out.n_conditions < 3 || out.n_quantities < 2 || out.n_data < 10;
  if (out.n_conditions >= 2) {
    std::set<double> speeds, flows;
    for (const auto& p : m.points()) {
      speeds.insert(d.stations[p.condition].belt_speed);
      flows.insert(d.stations[p.condition].mass_flow);
    }
    out.one_belt_speed = speeds.size() == 1;
    out.one_mass_flow = flows.size() == 1;
  }
  if (best) out.shape = shape_of(s, *best);
  out.verdict_code = verdict_of(out, best, outside);
  if (out.verdict_code == Verdict::missing_effect || out.verdict_code == Verdict::partial_explanation)
    out.record_scope = record_scope_of(s, best);
  out.convincing = out.verdict_code == Verdict::missing_effect;
  describe(out, opt);
  return out;
}

}  // namespace chutelab::validation
