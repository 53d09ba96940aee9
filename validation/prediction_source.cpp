#include "validation/prediction_source.h"

#include <atomic>
#include <exception>
#include <fmt/format.h>
#include <numeric>
#include <thread>
#include <unordered_map>

#include "core/input_error.h"
#include "core/interrupt.h"
#include "validation/campaign_runs.h"
#include "validation/harness.h"
#include "validation/parallel_runs.h"
#include "validation/response_pooling.h"
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

std::string strengths_key(std::span<const effects::EffectInfo* const> fx, std::span<const double> strengths) {
  std::string k;
  for (std::size_t i = 0; i < fx.size(); ++i) k += fmt::format("{}={:.17g};", fx[i]->name, strengths[i]);
  return k;
}

}  // namespace

PredictionSource::PredictionSource(const Dataset& d, std::vector<ModelPtr> models, analytical::EffectList fixed,
                                   int threads)
    : d_(&d), models_(std::move(models)), fixed_(std::move(fixed)), threads_(std::max(1, threads)),
      queries_(d.stations.size()), memo_(d.stations.size()), raw_fixed_(d.stations.size()) {
  // Look-ups by hash, once per row: a diagnosis stays linear in the size of the dataset.
  std::unordered_map<std::string, std::size_t> index;
  for (std::size_t i = 0; i < d.stations.size(); ++i) index.emplace(d.stations[i].condition, i);
  for (const auto& p : d.trajectory)
    if (auto it = index.find(p.condition); it != index.end()) queries_[it->second].push_back({p.boundary, p.x});
  // The cheap models carry effect signatures for an expensive one even when they are not among
  // the models being judged (e.g. --models dem).
  if (has_expensive())
    for (const auto& n : model_names())
      if (auto m = make_model(n); !m->expensive()) signature_.push_back(m);
  check_external_models(models_, d);
  // The baseline runs and their ladders, as one campaign.
  run_expensive(std::span(&fixed_, 1), true, false, "the baseline: every condition without candidate effects");
}

bool PredictionSource::has_expensive() const {
  for (const auto& m : models_)
    if (m->expensive()) return true;
  return false;
}

bool PredictionSource::reruns_expensive() const {
  for (const auto& m : models_)
    if (m->expensive() && m->runs_with_effects()) return true;
  return false;
}

analytical::EffectList PredictionSource::with(std::span<const effects::EffectInfo* const> fx,
                                              std::span<const double> strengths) const {
  analytical::EffectList list = fixed_;
  for (std::size_t i = 0; i < fx.size(); ++i) list.push_back(fx[i]->make(strengths[i]));
  return list;
}

std::vector<ConditionResult> PredictionSource::raw_condition(std::size_t c, const analytical::EffectList& list,
                                                             std::span<const effects::EffectInfo* const> fx,
                                                             std::span<const double> strengths, Evaluation how) const {
  const Station& st = d_->stations[c];
  std::vector<ConditionResult> same(models_.size());
  // The models that read the analytical chain share one analysis of the condition.
  std::optional<analytical::TransferAnalysis> chain;
  for (std::size_t k = 0; k < models_.size(); ++k) {
    if (models_[k]->reads_transfer_analysis()) {
      if (!chain) chain = analytical::analyse_transfer(st, list, &memo_[c]);
      same[k] = {st.condition, models_[k]->name(), models_[k]->predict_from(*chain, list, {queries_[c], false})};
    } else if (!models_[k]->expensive()) {
      same[k] = {st.condition, models_[k]->name(), models_[k]->predict(st, list, {queries_[c], false})};
    } else if (how == Evaluation::exact) {
      same[k] = {st.condition, models_[k]->name(), exact_run(c, k, fx, strengths)};
    }
  }
  return same;
}

bool PredictionSource::on_measurement_only(std::span<const effects::EffectInfo* const> fx) const {
  if (fx.empty() || has_expensive() || d_->stations.empty()) return false;
  auto same_numbers = [](const std::vector<ConditionResult>& a, const std::vector<ConditionResult>& b) {
    for (std::size_t k = 0; k < a.size(); ++k) {
      const ModelPrediction &x = a[k].prediction, &y = b[k].prediction;
      if (x.values.value != y.values.value || x.trajectory != y.trajectory || x.plate != y.plate) return false;
    }
    return true;
  };
  for (const auto* e : fx) {
    auto [it, fresh] = measurement_only_.try_emplace(e->name, false);
    if (fresh && e->stage == "measurement") try {
        analytical::EffectList on = fixed_;
        on.push_back(e->make(e->upper));
        it->second = same_numbers(raw_condition(0, fixed_, {}, {}, Evaluation::surrogate),
                                  raw_condition(0, on, {}, {}, Evaluation::surrogate));
      } catch (const InputError&) {
      }
    if (!it->second) return false;
  }
  return true;
}

void PredictionSource::predict_condition(std::size_t c, const analytical::EffectList& list,
                                         std::span<const effects::EffectInfo* const> fx,
                                         std::span<const double> strengths, Evaluation how, bool reuse_raw,
                                         std::vector<ModelPrediction>& out) const {
  const Station& st = d_->stations[c];
  // An effect of one condition's record applies there alone.
  if (!analytical::all_act_at(list, st)) {
    predict_condition(c, analytical::acting_at(list, st), fx, strengths, how, reuse_raw, out);
    return;
  }
  std::vector<ConditionResult> same;
  if (reuse_raw) {
    if (!raw_fixed_[c]) raw_fixed_[c] = raw_condition(c, fixed_, {}, {}, how);
    same = *raw_fixed_[c];
  } else {
    same = raw_condition(c, list, fx, strengths, how);
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
            if (auto d = shifts[i].value(*this, c, k, *fx[i], Value{q, 0})) *p.values[q] += *d;
      for (std::size_t t = 0; t < p.trajectory.size(); ++t)
        if (p.trajectory[t])
          for (std::size_t i = 0; i < fx.size(); ++i)
            if (auto d = shifts[i].value(*this, c, k, *fx[i], Value{std::nullopt, t})) *p.trajectory[t] += *d;
      same[k] = {st.condition, models_[k]->name(), std::move(p)};
    }
  }
  apply_measurement_effects(list, same);
  out.reserve(out.size() + same.size());
  for (auto& s : same) out.push_back(std::move(s.prediction));
}

Predictions PredictionSource::predict(std::span<const effects::EffectInfo* const> fx, std::span<const double> strengths,
                                      Evaluation how, std::span<const std::size_t> only) const {
  Predictions out(d_->stations.size());
  for_conditions(fx, strengths, how, only, [&](std::size_t c, std::vector<ModelPrediction>& p) { out[c] = std::move(p); });
  return out;
}

void PredictionSource::visit(std::span<const effects::EffectInfo* const> fx, std::span<const double> strengths,
                             Evaluation how, std::span<const std::size_t> only, const ConditionUse& use) const {
  for_conditions(fx, strengths, how, only, [&](std::size_t c, std::vector<ModelPrediction>& p) { use(c, p); });
}

void PredictionSource::for_conditions(std::span<const effects::EffectInfo* const> fx, std::span<const double> strengths,
                                      Evaluation how, std::span<const std::size_t> only,
                                      const std::function<void(std::size_t, std::vector<ModelPrediction>&)>& take) const {
  const analytical::EffectList list = with(fx, strengths);
  const bool reuse_raw = on_measurement_only(fx);
  std::vector<std::size_t> all;
  if (only.empty()) {
    all.resize(d_->stations.size());
    std::iota(all.begin(), all.end(), std::size_t{0});
    only = all;
  }
  const std::size_t n = only.size();
  // A model that cannot take a condition says which line of conditions.csv, as validate does.
  // `scratch` is the calling thread's: its predictions are made, used and freed there.
  auto condition = [&](std::size_t i, std::vector<ModelPrediction>& scratch) {
    const std::size_t c = only[i];
    scratch.clear();
    interrupt::point();
    try {
      predict_condition(c, list, fx, strengths, how, reuse_raw, scratch);
    } catch (const InputError& e) {
      if (c < d_->station_lines.size()) throw e.located(d_->station_lines[c].file, d_->station_lines[c].line);
      throw;
    }
    take(c, scratch);
  };
  // Conditions are independent and each writes only its own slot and memo, so they may go side by
  // side; the expensive models' caches are shared maps, so with one of them they go in order. A
  // failure is the first in the order asked, as in order: every condition before the first failure
  // found is still predicted. Workers take small blocks of conditions as they come free (a busy
  // machine may stall one of them), and the caller works too.
  const int threads = has_expensive() ? 1 : std::min<int>(threads_, static_cast<int>(n / kConditionsPerThread));
  if (threads <= 1) {
    std::vector<ModelPrediction> scratch;
    for (std::size_t i = 0; i < n; ++i) condition(i, scratch);
    return;
  }
  std::vector<std::exception_ptr> failure(n);
  std::atomic<std::size_t> next_block{0}, first_failure{n};
  constexpr std::size_t kBlock = 16;
  auto work = [&] {
    std::vector<ModelPrediction> scratch;
    for (std::size_t b; (b = next_block.fetch_add(kBlock)) < n;)
      for (std::size_t i = b; i < std::min(n, b + kBlock) && i < first_failure.load(); ++i) try {
          condition(i, scratch);
        } catch (...) {
          failure[i] = std::current_exception();
          for (std::size_t f = first_failure.load(); i < f && !first_failure.compare_exchange_weak(f, i);) {
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
}

PredictionSource::Shift PredictionSource::shift_of(std::size_t c, const effects::EffectInfo& e, double s) const {
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

std::optional<double> PredictionSource::Value::of(const ModelPrediction& mp) const {
  if (q) return mp.values[*q];
  return query < mp.trajectory.size() ? mp.trajectory[query] : std::nullopt;
}

std::optional<double> PredictionSource::Value::sd_of(const ModelPrediction& mp) const {
  if (q) return mp.uncertainty[*q];
  return query < mp.trajectory_uncertainty.size() ? mp.trajectory_uncertainty[query] : std::nullopt;
}

std::optional<double> PredictionSource::cheap_shift(std::size_t c, std::span<const ModelPrediction> with,
                                                    const Value& v) const {
  for (std::size_t j = 0; j < signature_.size() && j < with.size(); ++j) {
    const auto b = v.of(cheap_base(c, signature_[j]));
    if (!b) continue;
    const auto w = v.of(with[j]);
    if (!w) return std::nullopt;
    return *w - *b;
  }
  return std::nullopt;
}

const PredictionSource::OwnResponse& PredictionSource::own_response(std::size_t k, const effects::EffectInfo& e) const {
  const auto key = std::make_pair(k, e.name);
  if (auto it = own_response_cache_.find(key); it != own_response_cache_.end()) return it->second;
  const std::size_t n = d_->stations.size();
  OwnResponse out;
  out.values.resize(n);
  out.trajectory.resize(n);
  // Each condition's own difference, its sd and the cheap models' response at the probe strength.
  struct Entry {
    std::size_t c;
    Value v;
    double own, sd;
    std::optional<double> shape;
  };
  std::map<std::optional<Quantity>, std::vector<Entry>> pools;  // per quantity; every trajectory point in one
  analytical::EffectList at_p = fixed_;
  at_p.push_back(e.make(probe_strength(e)));
  out.failed.assign(n, false);
  for (std::size_t c = 0; c < n; ++c) {
    const ModelPrediction* probe_c = nullptr;
    try {
      probe_c = &expensive_probe(c, k, e);
    } catch (const InputError&) {
      out.failed[c] = true;  // that condition's problem: it surfaces where that condition is predicted
      continue;
    }
    const ModelPrediction &base = signature_base(c, k), &probe = *probe_c;
    std::vector<ModelPrediction> cheap_probe_c;
    for (const auto& m : signature_) {
      try {
        cheap_probe_c.push_back(m->predict(d_->stations[c], at_p, {queries_[c], false}));
      } catch (const InputError&) {
        cheap_probe_c.push_back({});
      }
    }
    auto add = [&](const Value& v) {
      const auto b = v.of(base), p = v.of(probe);
      if (!b || !p) return;
      const double sd = std::hypot(v.sd_of(base).value_or(0.0), v.sd_of(probe).value_or(0.0));
      pools[v.q].push_back({c, v, *p - *b, sd, cheap_shift(c, cheap_probe_c, v)});
    };
    for (Quantity q : kAllQuantities) add(Value{q, 0});
    out.trajectory[c].assign(base.trajectory.size(), std::nullopt);
    for (std::size_t t = 0; t < base.trajectory.size(); ++t) add(Value{std::nullopt, t});
  }
  for (const auto& [q, entries] : pools) {
    std::vector<double> own, sd;
    std::vector<std::optional<double>> shape;
    for (const auto& x : entries) own.push_back(x.own), sd.push_back(x.sd), shape.push_back(x.shape);
    const PooledResponse r = pool_responses(own, sd, shape);
    for (std::size_t i = 0; i < entries.size(); ++i) {
      const Entry& x = entries[i];
      if (q) out.values[x.c][*q] = r.response[i];
      else out.trajectory[x.c][x.v.query] = r.response[i];
    }
  }
  return own_response_cache_.emplace(key, std::move(out)).first->second;
}

std::optional<double> PredictionSource::Shift::value(const PredictionSource& src, std::size_t c, std::size_t k,
                                                     const effects::EffectInfo& e, const Value& v) const {
  if (!active) return 0.0;
  auto cheap = [&](const std::vector<ModelPrediction>& with) { return src.cheap_shift(c, with, v); };
  switch (src.signature(e)) {
    case Signature::none: return 0.0;
    case Signature::cheap_models: return cheap(cheap_at_s);
    case Signature::own_runs: break;
  }
  const OwnResponse& own = src.own_response(k, e);
  if (own.failed[c]) (void)src.expensive_probe(c, k, e);  // fails as the run does
  const std::optional<double> response =
      v.q ? own.values[c][*v.q] : v.query < own.trajectory[c].size() ? own.trajectory[c][v.query] : std::nullopt;
  if (!response) return cheap(cheap_at_s);
  const auto base = v.of(src.signature_base(c, k));
  // The model's own response at the probe strength, carried to s along the shape of the cheap
  // models' response (their nonlinearity in s), or linearly where they do not respond.
  const double sp = src.probe_strength(e);
  const double linear = (strength - e.neutral) / (sp - e.neutral);
  double ratio = linear;
  const auto cs = cheap(cheap_at_s), cp = cheap(cheap_at_probe);
  if (cs && cp && std::abs(*cp) > 1e-9 * (std::abs(*base) + 1e-12)) {
    const double r = *cs / *cp;
    // A cheap response that nearly vanishes at the probe would blow the ratio up: trust it only
    // within a few times the linear carry.
    if (std::abs(r) <= 4.0 * std::abs(linear) + 0.5) ratio = r;
  }
  return *response * ratio;
}

PredictionSource::Signature PredictionSource::signature(const effects::EffectInfo& e) const {
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

double PredictionSource::probe_strength(const effects::EffectInfo& e) const {
  if (auto it = probe_strength_cache_.find(e.name); it != probe_strength_cache_.end()) return it->second;
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
  probe_strength_cache_[e.name] = p;
  return p;
}

const ModelPrediction& PredictionSource::expensive_probe(std::size_t c, std::size_t k,
                                                         const effects::EffectInfo& e) const {
  auto& slot = probe_cache_[{c, k, e.name}];
  if (!slot) {
    analytical::EffectList with = fixed_;
    with.push_back(e.make(probe_strength(e)));
    slot = models_[k]->predict(d_->stations[c], with, {queries_[c], false, false, true});
  }
  return *slot;
}

const ModelPrediction& PredictionSource::signature_base(std::size_t c, std::size_t k) const {
  if (!models_[k]->cheaper_signatures()) return expensive_base(c, k);
  auto& slot = signature_base_cache_[{c, k}];
  if (!slot) slot = models_[k]->predict(d_->stations[c], fixed_, {queries_[c], false, false, true});
  return *slot;
}

// An effect on the measurement only is applied to a run's output afterwards: the run is the one
// without it (for no such effect at all, the baseline's standard run).
PredictionSource::RunPart PredictionSource::run_part(std::span<const effects::EffectInfo* const> fx,
                                                     std::span<const double> strengths) const {
  RunPart out;
  for (std::size_t i = 0; i < fx.size(); ++i)
    if (signature(*fx[i]) != Signature::none) {
      out.fx.push_back(fx[i]);
      out.strengths.push_back(strengths[i]);
    }
  return out;
}

const ModelPrediction& PredictionSource::exact_run(std::size_t c, std::size_t k,
                                                   std::span<const effects::EffectInfo* const> fx,
                                                   std::span<const double> strengths) const {
  const RunPart part = run_part(fx, strengths);
  if (part.fx.empty()) return expensive_base(c, k);
  auto& slot = exact_cache_[{c, k, strengths_key(part.fx, part.strengths)}];
  if (!slot) slot = models_[k]->predict(d_->stations[c], with(part.fx, part.strengths), {queries_[c], false, false});
  return *slot;
}

void PredictionSource::prepare_signatures(std::span<const effects::EffectInfo* const> candidates, int jobs) const {
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
    run_expensive(lists, false, true,
                  fmt::format("the signatures: every condition without candidates and with each of the {} candidates the "
                              "model runs itself, at its probe strength and at the signature quality where the model has one",
                              lists.size() - 1));
  }
  std::vector<std::function<void()>> work;
  // The baselines first, slots created here: the maps are not touched while the runs go on.
  for (std::size_t k = 0; k < models_.size(); ++k)
    if (models_[k]->expensive())
      for (std::size_t c = 0; c < d_->stations.size(); ++c)
        if (!expensive_cache_[{c, k}]) work.push_back([this, c, k] { (void)expensive_base(c, k); });
  if (any_own)
    for (std::size_t k = 0; k < models_.size(); ++k)
      if (models_[k]->expensive() && models_[k]->cheaper_signatures())
        for (std::size_t c = 0; c < d_->stations.size(); ++c)
          if (!signature_base_cache_[{c, k}]) work.push_back([this, c, k] { (void)signature_base(c, k); });
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

void PredictionSource::prepare_exact(std::span<const effects::EffectInfo* const> fx, std::span<const double> strengths,
                                     int jobs, const std::string& why) const {
  const RunPart part = run_part(fx, strengths);
  if (part.fx.empty()) return;  // the baseline's runs, made already
  const analytical::EffectList list = with(part.fx, part.strengths);
  std::vector<std::string> at;
  for (std::size_t i = 0; i < part.fx.size(); ++i) at.push_back(fmt::format("{} = {:.4g}", part.fx[i]->name, part.strengths[i]));
  // The runs as one campaign; the predictions below read them.
  run_expensive(std::span(&list, 1), false, false,
                fmt::format("{}every condition with {}", why.empty() ? std::string() : why + ": ", fmt::join(at, ", ")));
  std::vector<std::function<void()>> work;
  const std::string key = strengths_key(part.fx, part.strengths);
  for (std::size_t k = 0; k < models_.size(); ++k)
    if (models_[k]->expensive())
      for (std::size_t c = 0; c < d_->stations.size(); ++c)
        if (!exact_cache_[{c, k, key}]) work.push_back([this, c, k, fx, strengths] { (void)exact_run(c, k, fx, strengths); });
  run_concurrently(work, jobs);
}

const ModelPrediction& PredictionSource::expensive_base(std::size_t c, std::size_t k) const {
  auto& slot = expensive_cache_[{c, k}];
  if (!slot) slot = located_call(*d_, c, [&] { return models_[k]->predict(d_->stations[c], fixed_, {queries_[c], false}); });
  return *slot;
}

const ModelPrediction& PredictionSource::cheap_base(std::size_t c, const ModelPtr& m) const {
  auto& slot = cheap_cache_[{c, m->name()}];
  if (!slot) slot = located_call(*d_, c, [&] { return m->predict(d_->stations[c], fixed_, {queries_[c], false}); });
  return *slot;
}

void PredictionSource::run_expensive(std::span<const analytical::EffectList> lists, bool discretisation,
                                     bool signature, const std::string& purpose) const {
  std::vector<ModelRun> runs;
  for (const auto& effects : lists)
    for (std::size_t c = 0; c < d_->stations.size(); ++c)
      for (const auto& m : models_)
        if (m->expensive() && m->runs_with_effects())
          runs.push_back({m, d_->stations[c], effects, d_->station_lines[c].file, d_->station_lines[c].line, signature,
                          discretisation});
  run_models(runs, {"diagnose", threads_, purpose});
}

}  // namespace chutelab::validation
