#include "validation/effect_fit.h"

#include "analytical/transfer_station.h"

#include <Eigen/Dense>
#include <atomic>
#include <exception>
#include <cmath>
#include <fmt/format.h>
#include <functional>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_multifit_nlinear.h>
#include <limits>
#include <thread>
#include <unordered_map>

#include "core/input_error.h"
#include "validation/campaign_runs.h"
#include "validation/harness.h"
#include "validation/input_uncertainty.h"
#include "validation/parallel_runs.h"
#include "validation/models/external_model.h"

namespace chutelab::validation {
namespace {
template <class F>
ModelPrediction located_call(const Dataset& d, std::size_t c, F&& f) {
  try {
    return f();
  } catch (const InputError& e) {
    if (c < d.station_lines.size()) throw e.located(d.station_lines[c].file, d.station_lines[c].line);
    throw;
  }
}
}  // namespace

Misfit::Misfit(const Dataset& d, std::vector<ModelPtr> models, analytical::EffectList fixed, int threads)
    : d_(&d), models_(std::move(models)), fixed_(std::move(fixed)), threads_(std::max(1, threads)),
      memo_(d.stations.size()) {
  // Look-ups by hash, once per row: the diagnosis stays linear in the size of the dataset.
  std::unordered_map<std::string, std::size_t> index;
  for (std::size_t i = 0; i < d.stations.size(); ++i) index.emplace(d.stations[i].condition, i);
  queries_.resize(d.stations.size());
  for (const auto& p : d.trajectory)
    if (auto it = index.find(p.condition); it != index.end()) queries_[it->second].push_back({p.boundary, p.x});
  // The cheap models carry effect signatures for an expensive one even when they are not among
  // the models being judged (e.g. --models dem).
  if (has_expensive())
    for (const auto& n : model_names())
      if (auto m = make_model(n); !m->expensive()) signature_.push_back(m);
  check_external_models(models_, d);
  run_expensive(fixed_, true);  // the baseline runs and their ladders, as one campaign (MPI ranks, --jobs)
  const auto base = predict_all({}, {});
  auto condition_index = [&](const std::string& c) {
    if (auto it = index.find(c); it != index.end()) return it->second;
    throw std::logic_error("measurement of an unknown condition");
  };
  // chi^2 weights: u_D combined with the baseline prediction's u_num (statistical and
  // discretisation parts) and u_input, as V&V 20's u_val.
  std::map<std::pair<std::size_t, std::size_t>, InputUncertaintyResult> u_input;
  auto input_part = [&](std::size_t ci, std::size_t k) -> const InputUncertaintyResult& {
    auto [it, fresh] = u_input.try_emplace({ci, k});
    if (fresh && ci < d.input_uncertainty.size() && !d.input_uncertainty[ci].empty())
      it->second = input_uncertainty(*models_[k], d.stations[ci], d.input_uncertainty[ci], fixed_,
                                     queries_[ci], base[ci][k]);
    return it->second;
  };
  auto weight = [](double u_d, std::initializer_list<std::optional<double>> parts) {
    double sum = u_d * u_d;
    for (const auto& u : parts) sum += std::pow(u.value_or(0.0), 2);
    return std::sqrt(sum);
  };
  for (const auto& m : d.measurements) {
    const std::size_t ci = condition_index(m.condition);
    std::optional<std::size_t> by;
    for (std::size_t k = 0; k < models_.size() && !by; ++k)
      if (base[ci][k].values[m.quantity]) by = k;
    if (!by || !m.uncertainty) {
      ++left_out_;
      continue;
    }
    const ModelPrediction& b = base[ci][*by];
    const double u = weight(*m.uncertainty, {b.uncertainty[m.quantity], b.discretisation[m.quantity],
                                             input_part(ci, *by).u[m.quantity]});
    points_.push_back({ci, std::string(name(m.quantity)), m.quantity, 0, *by, m.value, u});
  }
  std::vector<std::size_t> next(d.stations.size(), 0);
  for (const auto& p : d.trajectory) {
    const std::size_t ci = condition_index(p.condition);
    const std::size_t qi = next[ci]++;
    std::optional<std::size_t> by;
    for (std::size_t k = 0; k < models_.size() && !by; ++k)
      if (qi < base[ci][k].trajectory.size() && base[ci][k].trajectory[qi]) by = k;
    if (!by || !p.uncertainty) {
      ++left_out_;
      continue;
    }
    const ModelPrediction& b = base[ci][*by];
    auto nth = [qi](const std::vector<std::optional<double>>& v) {
      return qi < v.size() ? v[qi] : std::nullopt;
    };
    const double u = weight(*p.uncertainty, {nth(b.trajectory_uncertainty), nth(b.trajectory_discretisation),
                                             nth(input_part(ci, *by).trajectory)});
    points_.push_back({ci, trajectory_quantity(p.boundary), std::nullopt, qi, *by, p.y, u});
  }
}

std::vector<std::vector<ModelPrediction>> Misfit::predict_all(
    std::span<const effects::EffectInfo* const> fx, std::span<const double> strengths) const {
  return predict(fx, strengths, Evaluation::surrogate);
}

std::vector<std::vector<ModelPrediction>> Misfit::predict(std::span<const effects::EffectInfo* const> fx,
                                                          std::span<const double> strengths,
                                                          Evaluation how) const {
  analytical::EffectList list = fixed_;
  for (std::size_t i = 0; i < fx.size(); ++i) list.push_back(fx[i]->make(strengths[i]));
  const std::size_t n = d_->stations.size();
  std::vector<std::vector<ModelPrediction>> out(n);
  auto condition = [&](std::size_t c) {
    const Station& st = d_->stations[c];
    // A model that cannot take a condition says which line of conditions.csv, as validate does.
    try {
    std::vector<ConditionResult> same(models_.size());
    // The models that read the analytical chain share one analysis of the condition.
    std::optional<analytical::TransferAnalysis> chain;
    for (std::size_t k = 0; k < models_.size(); ++k) {
      if (models_[k]->reads_transfer_analysis()) {
        if (!chain) chain = analytical::analyse_transfer(st, list, &memo_[c]);
        same[k] = {st.condition, models_[k]->name(), models_[k]->predict_from(*chain, list, {queries_[c], false})};
      } else if (!models_[k]->expensive())
        same[k] = {st.condition, models_[k]->name(), models_[k]->predict(st, list, {queries_[c], false})};
      else if (how == Evaluation::exact)
        same[k] = {st.condition, models_[k]->name(), exact_run(c, k, fx, strengths)};
    }
    if (how == Evaluation::surrogate && has_expensive()) {
      // Each candidate's shift of an expensive model, summed over the candidates (superposition):
      // from the model's own probe run, or from the cheap models (DESIGN.md §5).
      std::vector<Shift> shifts;
      for (std::size_t i = 0; i < fx.size(); ++i) shifts.push_back(shift_of(c, *fx[i], strengths[i]));
      for (std::size_t k = 0; k < models_.size(); ++k) {
        if (!models_[k]->expensive()) continue;
        ModelPrediction p = expensive_base(c, k);
        for (Quantity q : kAllQuantities)
          if (p.values[q])
            for (std::size_t i = 0; i < fx.size(); ++i)
              if (auto d = shifts[i].value(*this, c, k, *fx[i], [q](const ModelPrediction& mp) { return mp.values[q]; }))
                *p.values[q] += *d;
        for (std::size_t t = 0; t < p.trajectory.size(); ++t)
          if (p.trajectory[t])
            for (std::size_t i = 0; i < fx.size(); ++i)
              if (auto d = shifts[i].value(*this, c, k, *fx[i], [t](const ModelPrediction& mp) {
                    return t < mp.trajectory.size() ? mp.trajectory[t] : std::nullopt;
                  }))
                *p.trajectory[t] += *d;
        same[k] = {st.condition, models_[k]->name(), std::move(p)};
      }
    }
    apply_measurement_effects(list, same);
    for (auto& s : same) out[c].push_back(std::move(s.prediction));
    } catch (const InputError& e) {
      if (c < d_->station_lines.size()) throw e.located(d_->station_lines[c].file, d_->station_lines[c].line);
      throw;
    }
  };
  // Conditions are independent and each writes only its own slot and memo, so they may go side by
  // side; the expensive models' caches are shared maps, so with one of them they go in order. A
  // failure is the first in condition order, as in order: every condition before the first failure
  // found is still predicted. Workers take small blocks of conditions as they come free (a busy
  // machine may stall one of them), and the caller works too.
  const int threads = has_expensive() ? 1 : std::min<int>(threads_, static_cast<int>(n / kConditionsPerThread));
  if (threads <= 1) {
    for (std::size_t c = 0; c < n; ++c) condition(c);
    return out;
  }
  std::vector<std::exception_ptr> failure(n);
  std::atomic<std::size_t> next_block{0}, first_failure{n};
  constexpr std::size_t kBlock = 16;
  auto work = [&] {
    for (std::size_t b; (b = next_block.fetch_add(kBlock)) < n;)
      for (std::size_t c = b; c < std::min(n, b + kBlock) && c < first_failure.load(); ++c) try {
          condition(c);
        } catch (...) {
          failure[c] = std::current_exception();
          for (std::size_t f = first_failure.load(); c < f && !first_failure.compare_exchange_weak(f, c);) {
          }
        }
  };
  {
    std::vector<std::jthread> helpers;
    for (int t = 1; t < threads; ++t) helpers.emplace_back(work);
    work();
  }
  for (const auto& f : failure)
    if (f) std::rethrow_exception(f);
  return out;
}

Misfit::Shift Misfit::shift_of(std::size_t c, const effects::EffectInfo& e, double s) const {
  Shift sh;
  sh.strength = s;
  if (s == e.neutral) return sh;
  // Raw predictions of the cheap models (before measurement effects, which act on every model
  // afterwards) with the effect alone at s and at the probe strength.
  analytical::EffectList at_s = fixed_, at_p = fixed_;
  at_s.push_back(e.make(s));
  at_p.push_back(e.make(probe_strength(e)));
  const Station& st = d_->stations[c];
  for (const auto& m : signature_) {
    sh.cheap_at_s.push_back(m->predict(st, at_s, {queries_[c], false}));
    try {
      sh.cheap_at_probe.push_back(m->predict(st, at_p, {queries_[c], false}));
    } catch (const InputError&) {
      sh.cheap_at_probe.push_back({});  // no analytical shape there: the own response is carried linearly
    }
  }
  sh.active = true;
  return sh;
}

std::optional<double> Misfit::Shift::value(const Misfit& m, std::size_t c, std::size_t k, const effects::EffectInfo& e,
                                           const std::function<std::optional<double>(const ModelPrediction&)>& pick) const {
  if (!active) return 0.0;
  // The cheap models' shift: the first of them (registry order) that predicts the value.
  auto cheap = [&](const std::vector<ModelPrediction>& with) -> std::optional<double> {
    for (std::size_t j = 0; j < m.signature_.size(); ++j) {
      const auto b = pick(m.cheap_base(c, m.signature_[j]));
      if (!b) continue;
      const auto w = pick(with[j]);
      if (!w) return std::nullopt;
      return *w - *b;
    }
    return std::nullopt;
  };
  switch (m.signature(e)) {
    case Signature::none: return 0.0;
    case Signature::cheap_models: return cheap(cheap_at_s);
    case Signature::own_runs: break;
  }
  const auto base = pick(m.signature_base(c, k));
  const auto probe = pick(m.expensive_probe(c, k, e));
  if (!base || !probe) return cheap(cheap_at_s);
  // The model's own response at the probe strength, carried to s along the shape of the cheap
  // models' response (their nonlinearity in s), or linearly where they do not respond.
  const double sp = m.probe_strength(e);
  const double linear = (strength - e.neutral) / (sp - e.neutral);
  double ratio = linear;
  const auto cs = cheap(cheap_at_s), cp = cheap(cheap_at_probe);
  if (cs && cp && std::abs(*cp) > 1e-9 * (std::abs(*base) + 1e-12)) {
    const double r = *cs / *cp;
    // A cheap response that nearly vanishes at the probe would blow the ratio up: trust it only
    // within a few times the linear carry.
    if (std::abs(r) <= 4.0 * std::abs(linear) + 0.5) ratio = r;
  }
  return (*probe - *base) * ratio;
}

Misfit::Signature Misfit::signature(const effects::EffectInfo& e) const {
  if (auto it = signature_cache_.find(e.name); it != signature_cache_.end()) return it->second;
  Signature s = Signature::none;
  if (has_expensive()) {
    analytical::EffectList with = fixed_;
    with.push_back(e.make(probe_strength(e)));
    bool own = false, any_cheap = false;
    for (const auto& m : models_)
      if (m->expensive())
        for (const auto& st : d_->stations) own = own || m->represents(st, fixed_, with);
    // Does the effect change any raw prediction of the cheap models (not only the measurement)?
    if (!own)
      for (std::size_t c = 0; c < d_->stations.size() && !any_cheap; ++c)
        for (const auto& m : signature_) {
          try {
            const auto a = m->predict(d_->stations[c], with, {queries_[c], false});
            const auto& b = cheap_base(c, m);
            for (Quantity q : kAllQuantities) any_cheap = any_cheap || a.values[q] != b.values[q];
            any_cheap = any_cheap || a.trajectory != b.trajectory;
          } catch (const InputError&) {
            any_cheap = true;  // it changes the analytical chain so much that it has no answer there
          }
        }
    s = own ? Signature::own_runs : any_cheap ? Signature::cheap_models : Signature::none;
  }
  signature_cache_[e.name] = s;
  return s;
}

double Misfit::probe_strength(const effects::EffectInfo& e) const {
  if (auto it = probe_cache_strength_.find(e.name); it != probe_cache_strength_.end()) return it->second;
  // Twice the typical strength, inside the physical range: large enough for the response to stand
  // out of a DEM's noise, small enough to stay near the linear regime. Where the analytical chain
  // has no answer there at some condition (a holding stress the stream cannot escape), the typical
  // strength itself.
  const double twice = std::clamp(e.neutral + 2.0 * (e.typical - e.neutral), e.lower, e.upper);
  double p = twice;
  try {
    analytical::EffectList with = fixed_;
    with.push_back(e.make(twice));
    for (std::size_t c = 0; c < d_->stations.size(); ++c)
      for (const auto& m : signature_) (void)m->predict(d_->stations[c], with, {queries_[c], false});
  } catch (const InputError&) {
    p = std::clamp(e.typical, e.lower, e.upper);
  }
  probe_cache_strength_[e.name] = p;
  return p;
}

const ModelPrediction& Misfit::expensive_probe(std::size_t c, std::size_t k, const effects::EffectInfo& e) const {
  auto& slot = probe_cache_[{c, k, e.name}];
  if (!slot) {
    analytical::EffectList with = fixed_;
    with.push_back(e.make(probe_strength(e)));
    slot = models_[k]->predict(d_->stations[c], with, {queries_[c], false, false, true});
  }
  return *slot;
}

const ModelPrediction& Misfit::signature_base(std::size_t c, std::size_t k) const {
  if (!models_[k]->cheaper_signatures()) return expensive_base(c, k);
  auto& slot = signature_base_cache_[{c, k}];
  if (!slot) slot = models_[k]->predict(d_->stations[c], fixed_, {queries_[c], false, false, true});
  return *slot;
}

namespace {
std::string strengths_key(std::span<const effects::EffectInfo* const> fx, std::span<const double> strengths) {
  std::string k;
  for (std::size_t i = 0; i < fx.size(); ++i) k += fmt::format("{}={:.17g};", fx[i]->name, strengths[i]);
  return k;
}
}  // namespace

const ModelPrediction& Misfit::exact_run(std::size_t c, std::size_t k, std::span<const effects::EffectInfo* const> fx,
                                         std::span<const double> strengths) const {
  auto& slot = exact_cache_[{c, k, strengths_key(fx, strengths)}];
  if (!slot) {
    analytical::EffectList list = fixed_;
    for (std::size_t i = 0; i < fx.size(); ++i) list.push_back(fx[i]->make(strengths[i]));
    slot = models_[k]->predict(d_->stations[c], list, {queries_[c], false, false});
  }
  return *slot;
}

void Misfit::prepare_signatures(std::span<const effects::EffectInfo* const> candidates, int jobs) const {
  // The runs themselves as campaigns (spread over MPI ranks or --jobs); the predictions below then
  // read their results. Probe runs go at the signature quality, where the model has a cheaper one.
  bool any_own = false;
  for (const auto* e : candidates) any_own = any_own || signature(*e) == Signature::own_runs;
  if (any_own) {
    // The signature baseline (for a model without a cheaper quality it is the baseline, already
    // run) and one probe per candidate.
    std::vector<analytical::EffectList> lists = {fixed_};
    for (const auto* e : candidates)
      if (signature(*e) == Signature::own_runs) {
        lists.push_back(fixed_);
        lists.back().push_back(e->make(probe_strength(*e)));
      }
    run_expensive(lists, false, true);
  }
  std::vector<std::function<void()>> work;
  // The baselines first, slots created here: the maps are not touched while the runs go on.
  for (std::size_t k = 0; k < models_.size(); ++k)
    if (models_[k]->expensive())
      for (std::size_t c = 0; c < d_->stations.size(); ++c)
        if (!expensive_cache_[{c, k}]) work.push_back([this, c, k] { (void)expensive_base(c, k); });
  for (const auto* e : candidates)
    if (signature(*e) == Signature::own_runs) {
      for (std::size_t k = 0; k < models_.size(); ++k)
        if (models_[k]->expensive() && models_[k]->cheaper_signatures())
          for (std::size_t c = 0; c < d_->stations.size(); ++c)
            if (!signature_base_cache_[{c, k}]) work.push_back([this, c, k] { (void)signature_base(c, k); });
      break;
    }
  run_concurrently(work, jobs);
  work.clear();
  for (const auto* e : candidates)
    if (signature(*e) == Signature::own_runs)
      for (std::size_t k = 0; k < models_.size(); ++k)
        if (models_[k]->expensive())
          for (std::size_t c = 0; c < d_->stations.size(); ++c)
            if (!probe_cache_[{c, k, e->name}]) work.push_back([this, c, k, e] { (void)expensive_probe(c, k, *e); });
  run_concurrently(work, jobs);
}

void Misfit::prepare_exact(std::span<const effects::EffectInfo* const> fx, std::span<const double> strengths,
                           int jobs) const {
  {
    analytical::EffectList list = fixed_;
    for (std::size_t i = 0; i < fx.size(); ++i) list.push_back(fx[i]->make(strengths[i]));
    run_expensive(list, false);  // the runs as one campaign; the predictions below read them
  }
  std::vector<std::function<void()>> work;
  const std::string key = strengths_key(fx, strengths);
  for (std::size_t k = 0; k < models_.size(); ++k)
    if (models_[k]->expensive())
      for (std::size_t c = 0; c < d_->stations.size(); ++c)
        if (!exact_cache_[{c, k, key}]) work.push_back([this, c, k, fx, strengths] { (void)exact_run(c, k, fx, strengths); });
  run_concurrently(work, jobs);
}

const ModelPrediction& Misfit::expensive_base(std::size_t c, std::size_t k) const {
  auto& slot = expensive_cache_[{c, k}];
  if (!slot) slot = located_call(*d_, c, [&] { return models_[k]->predict(d_->stations[c], fixed_, {queries_[c], false}); });
  return *slot;
}

const ModelPrediction& Misfit::cheap_base(std::size_t c, const ModelPtr& m) const {
  auto& slot = cheap_cache_[{c, m->name()}];
  if (!slot) slot = located_call(*d_, c, [&] { return m->predict(d_->stations[c], fixed_, {queries_[c], false}); });
  return *slot;
}

bool Misfit::has_expensive() const {
  for (const auto& m : models_)
    if (m->expensive()) return true;
  return false;
}

void Misfit::run_expensive(std::span<const analytical::EffectList> lists, bool discretisation, bool signature) const {
  std::vector<ModelRun> runs;
  for (const auto& effects : lists)
    for (std::size_t c = 0; c < d_->stations.size(); ++c)
      for (const auto& m : models_)
        if (m->expensive() && m->runs_with_effects())
          runs.push_back({m, d_->stations[c], effects, d_->station_lines[c].file, d_->station_lines[c].line, signature,
                          discretisation});
  run_models(runs, {"diagnose"});
}

double Misfit::chi2_exact(std::span<const effects::EffectInfo* const> fx,
                          std::span<const double> strengths) const {
  analytical::EffectList list = fixed_;
  for (std::size_t i = 0; i < fx.size(); ++i) list.push_back(fx[i]->make(strengths[i]));
  run_expensive(list, false);  // the confirmation runs, as one campaign
  return chi2_of(predict(fx, strengths, Evaluation::exact));
}

std::vector<double> Misfit::residuals(std::span<const effects::EffectInfo* const> fx,
                                      std::span<const double> strengths) const {
  // Off the map: the misfit of a model that predicts nothing useful, large but finite so that
  // the minimiser can still step back.
  constexpr double kInfeasible = 1e3;
  try {
    return residuals_of(predict_all(fx, strengths));
  } catch (const InputError&) {
    return std::vector<double>(points_.size(), kInfeasible);
  }
}

std::vector<double> Misfit::residuals_of(const std::vector<std::vector<ModelPrediction>>& pred) const {
  std::vector<double> r(points_.size());
  for (std::size_t i = 0; i < points_.size(); ++i) {
    const auto& p = points_[i];
    const ModelPrediction& mp = pred[p.condition][p.model];
    std::optional<double> v;
    if (p.q) v = mp.values[*p.q];
    else if (p.query < mp.trajectory.size()) v = mp.trajectory[p.query];
    // A prediction that an effect makes vanish (Korzen's V_a when stationary flow stops) counts as
    // zero: the effect has to explain the measurement, not remove it.
    r[i] = (v.value_or(0.0) - p.measured) / p.uncertainty;
  }
  return r;
}

double Misfit::chi2_of(const std::vector<std::vector<ModelPrediction>>& pred) const {
  double s = 0.0;
  for (double x : residuals_of(pred)) s += x * x;
  return s;
}

double Misfit::chi2(std::span<const effects::EffectInfo* const> fx,
                    std::span<const double> strengths) const {
  double s = 0.0;
  for (double x : residuals(fx, strengths)) s += x * x;
  return s;
}

namespace {

// Bounds by a logistic map: p = lo + (hi - lo) / (1 + e^-u) keeps every trial inside the range.
double to_p(double u, double lo, double hi) { return lo + (hi - lo) / (1.0 + std::exp(-u)); }
double to_u(double p, double lo, double hi) {
  const double f = std::clamp((p - lo) / (hi - lo), 1e-9, 1.0 - 1e-9);
  return std::log(f / (1.0 - f));
}

struct GslContext {
  const Misfit* m;
  std::span<const effects::EffectInfo* const> fx;
};

int gsl_residuals(const gsl_vector* u, void* params, gsl_vector* f) {
  const auto* ctx = static_cast<GslContext*>(params);
  std::vector<double> p(ctx->fx.size());
  for (std::size_t i = 0; i < p.size(); ++i)
    p[i] = to_p(gsl_vector_get(u, i), ctx->fx[i]->lower, ctx->fx[i]->upper);
  const auto r = ctx->m->residuals(ctx->fx, p);
  for (std::size_t i = 0; i < r.size(); ++i) gsl_vector_set(f, i, r[i]);
  return GSL_SUCCESS;
}

// Grid over the physical range, finer for one parameter than for two.
void grid_scan(const Misfit& m, std::span<const effects::EffectInfo* const> fx,
               std::vector<double>& best, double& best_chi2) {
  const int n = fx.size() == 1 ? 40 : 5;
  std::vector<double> p(fx.size());
  std::vector<int> idx(fx.size(), 0);
  while (true) {
    for (std::size_t i = 0; i < fx.size(); ++i)
      p[i] = fx[i]->lower + (fx[i]->upper - fx[i]->lower) * idx[i] / n;
    const double c = m.chi2(fx, p);
    if (c < best_chi2) {
      best_chi2 = c;
      best = p;
    }
    std::size_t k = 0;
    while (k < idx.size() && ++idx[k] > n) idx[k++] = 0;
    if (k == idx.size()) break;
  }
}

}  // namespace

StrengthFit fit_strengths(const Misfit& m, std::span<const effects::EffectInfo* const> fx,
                          const std::vector<std::vector<double>>& starts) {
  gsl_set_error_handler_off();
  const std::size_t k = fx.size();
  StrengthFit out;
  std::vector<double> best(k);
  for (std::size_t i = 0; i < k; ++i) best[i] = fx[i]->neutral;
  double best_chi2 = m.chi2(fx, best);
  for (const auto& s : starts)
    if (s.size() == k) {
      const double c = m.chi2(fx, s);
      if (c < best_chi2) {
        best_chi2 = c;
        best = s;
      }
    }
  grid_scan(m, fx, best, best_chi2);

  if (m.size() > k) {
    GslContext ctx{&m, fx};
    gsl_multifit_nlinear_fdf fdf{};
    fdf.f = gsl_residuals;
    fdf.df = nullptr;  // forward-difference Jacobian
    fdf.n = m.size();
    fdf.p = k;
    fdf.params = &ctx;
    gsl_multifit_nlinear_parameters par = gsl_multifit_nlinear_default_parameters();
    gsl_multifit_nlinear_workspace* w =
        gsl_multifit_nlinear_alloc(gsl_multifit_nlinear_trust, &par, m.size(), k);
    gsl_vector* u = gsl_vector_alloc(k);
    for (std::size_t i = 0; i < k; ++i) gsl_vector_set(u, i, to_u(best[i], fx[i]->lower, fx[i]->upper));
    int info = 0;
    gsl_multifit_nlinear_init(u, &fdf, w);
    const int status = gsl_multifit_nlinear_driver(100, 1e-10, 1e-10, 1e-12, nullptr, nullptr, &info, w);
    std::vector<double> p(k);
    for (std::size_t i = 0; i < k; ++i)
      p[i] = to_p(gsl_vector_get(w->x, i), fx[i]->lower, fx[i]->upper);
    const double c = m.chi2(fx, p);
    out.converged = status == GSL_SUCCESS;
    if (c <= best_chi2) {
      best_chi2 = c;
      best = p;
    }
    gsl_vector_free(u);
    gsl_multifit_nlinear_free(w);
  }
  out.estimate = best;
  out.chi2 = best_chi2;

  // Uncertainty in the parameters' own units: central differences of the residuals give J, and
  // the covariance of a weighted least-squares estimate is (J^T J)^-1.
  Eigen::MatrixXd J(m.size(), k);
  for (std::size_t j = 0; j < k; ++j) {
    const double h = 1e-4 * (fx[j]->upper - fx[j]->lower);
    std::vector<double> lo = best, hi = best;
    lo[j] = std::max(fx[j]->lower, best[j] - h);
    hi[j] = std::min(fx[j]->upper, best[j] + h);
    const auto rl = m.residuals(fx, lo), rh = m.residuals(fx, hi);
    for (std::size_t i = 0; i < m.size(); ++i) J(i, j) = (rh[i] - rl[i]) / (hi[j] - lo[j]);
  }
  const Eigen::MatrixXd JtJ = J.transpose() * J;
  Eigen::FullPivLU<Eigen::MatrixXd> lu(JtJ);
  out.uncertainty.assign(k, std::numeric_limits<double>::infinity());
  if (lu.isInvertible() && lu.rcond() > 1e-12) {
    const Eigen::MatrixXd cov = lu.inverse();
    for (std::size_t j = 0; j < k; ++j) out.uncertainty[j] = std::sqrt(std::max(0.0, cov(j, j)));
  }
  return out;
}

}  // namespace chutelab::validation
