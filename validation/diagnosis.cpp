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