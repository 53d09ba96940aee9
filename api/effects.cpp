#include "api/effects.h"

#include <algorithm>
#include <fmt/format.h>

#include "core/input_error.h"
#include "effects/at_condition.h"
#include "effects/registry.h"
#include "validation/strength_fit.h"

namespace chutelab::api {
namespace {

// An effect applied, in the report's words. What the report says of a registered effect (a
// corrected record and the measurement that checks it) is looked up by the effect's own name: a
// record at one condition (NAME@CONDITION) is no registered name and is said as physics.
reports::EffectDescription describe(const effects::EffectInfo& e, double value, std::optional<double> uncertainty,
                                    bool fitted) {
  reports::EffectDescription d{e.name, e.parameter, e.unit, e.physics, e.source, value, uncertainty, fitted};
  // A record at one condition (NAME@CONDITION) is that record: its kind and check are the record's.
  if (const auto* registered = effects::find_candidate(e.name)) {
    d.record = registered->kind == effects::EffectInfo::Kind::record;
    d.check = registered->check;
  }
  return d;
}

}  // namespace

std::vector<validation::ModelPtr> in_registry_order(const std::vector<validation::ModelPtr>& models) {
  const auto order = validation::model_names();
  auto pos = [&](const validation::ModelPtr& m) {
    return std::find(order.begin(), order.end(), m->name()) - order.begin();
  };
  auto sorted = models;
  std::stable_sort(sorted.begin(), sorted.end(), [&](const auto& a, const auto& b) { return pos(a) < pos(b); });
  return sorted;
}

std::vector<std::string> effects_and_inputs(const std::vector<std::string>& effects,
                                            const std::vector<std::string>& inputs, bool allow_fit,
                                            bool outside_range) {
  std::vector<std::string> out = effects;
  std::vector<const effects::EffectInfo*> seen;
  for (const auto& a : inputs) {
    const std::string name = a.substr(0, a.find('='));
    const auto* e = effects::find(effects::split_condition(name).first);
    if (!e || e->kind != effects::EffectInfo::Kind::record) {
      std::vector<std::string> names;
      for (const auto& i : effects::library())
        if (i.kind == effects::EffectInfo::Kind::record) names.push_back(fmt::format("{} ({})", i.name, i.unit.empty() ? "fraction" : i.unit));
      throw InputError("", 0, "input",
                       fmt::format("'{}' is {}; {} takes a recorded input and its error, truth minus record "
                                   "(NAME@CONDITION: at that condition alone): {}",
                                   name, e ? "a physical effect (give it with " + mention("effect") + ")" : "not a recorded input",
                                   mention("input"), fmt::join(names, ", ")));
    }
    const auto s = effects::parse_setting(a, allow_fit, outside_range, "input");
    if (std::find(seen.begin(), seen.end(), s.info) != seen.end())
      throw InputError("", 0, "input", fmt::format("{} given twice", s.info->name));
    seen.push_back(s.info);
    out.push_back(a);
  }
  return out;
}

ParsedEffects parse_effects(const std::vector<std::string>& args) {
  ParsedEffects parsed;
  auto& fixed = parsed.fixed;
  auto& to_fit = parsed.to_fit;
  for (const auto& a : args) {
    auto s = effects::parse_setting(a, true);
    for (const auto& seen : fixed)
      if (seen.info == s.info) throw InputError("", 0, "effect", fmt::format("{} given twice", s.info->name));
    for (const auto& seen : to_fit)
      if (seen.info == s.info) throw InputError("", 0, "effect", fmt::format("{} given twice", s.info->name));
    (s.value ? fixed : to_fit).push_back(s);
  }
  // The joint fit's time grows about five-fold with each effect fitted (measured on grima2010-sized
  // datasets: 4 effects 1.6 s, 6 effects 47 s, 9 past 300 s): refused before it starts rather than
  // left to run for hours without a word.
  constexpr std::size_t kMaxJointFit = 5;
  if (to_fit.size() > kMaxJointFit)
    throw InputError("", 0, "effect",
                     fmt::format("{} effects to fit at once: the joint fit's time grows about five-fold with each "
                                 "(6 take a minute, 9 hours); fit at most {} together and give the others a value "
                                 "(NAME=VALUE)",
                                 to_fit.size(), kMaxJointFit));
  return parsed;
}

AppliedEffects resolve_effects(const std::vector<std::string>& args, const validation::Dataset& d,
                               const std::vector<validation::ModelPtr>& models,
                               std::vector<reports::EffectDescription>& described,
                               const analytical::EffectList& also) {
  const auto [fixed, to_fit] = parse_effects(args);
  AppliedEffects out;
  out.effects = effects::instantiate(fixed);
  for (const auto& s : fixed) {
    out.labels.push_back(fmt::format("{}={}", s.info->name, *s.value));
    described.push_back(describe(*s.info, *s.value, std::nullopt, false));
  }
  if (to_fit.empty()) return out;

  analytical::EffectList applied = out.effects;
  applied.insert(applied.end(), also.begin(), also.end());
  const validation::Misfit misfit(d, in_registry_order(models), applied);
  if (misfit.size() == 0)
    throw InputError(d.dir.string(), 0, "effect",
                     "nothing to fit: no measurement with an uncertainty that these models predict");
  std::vector<const effects::EffectInfo*> fx;
  for (const auto& s : to_fit) fx.push_back(s.info);
  const auto fit = validation::fit_strengths(misfit, fx);
  for (std::size_t i = 0; i < fx.size(); ++i) {
    out.effects.push_back(fx[i]->make(fit.estimate[i]));
    out.labels.push_back(fmt::format("{}={:.4g} (fitted)", fx[i]->name, fit.estimate[i]));
    described.push_back(describe(*fx[i], fit.estimate[i], fit.uncertainty[i], true));
  }
  out.notes.push_back(fmt::format(
      "Fitted on this dataset ({} values with uncertainties): chi^2 {:.1f} -> {:.1f}.", misfit.size(),
      misfit.chi2({}, {}), fit.chi2));
  return out;
}

AppliedEffects diagnosed_effects(const validation::DiagnosisResult& diagnosis, const std::vector<std::string>& skip,
                                 std::vector<reports::EffectDescription>& described) {
  AppliedEffects out;
  const validation::EffectFit* best = diagnosis.best();
  if (!best) return out;
  for (std::size_t i = 0; i < best->effects.size(); ++i) {
    const auto* e = effects::find_candidate(best->effects[i]);
    if (std::find(skip.begin(), skip.end(), e->name) != skip.end()) continue;
    out.effects.push_back(e->make(best->estimate[i]));
    out.labels.push_back(fmt::format("{}={:.4g} (fitted)", e->name, best->estimate[i]));
    described.push_back(describe(*e, best->estimate[i], best->uncertainty[i], true));
  }
  if (out.effects.empty()) return out;
  out.notes.push_back(fmt::format(
      "{} as the diagnosis fitted {} ({} values with uncertainties, under its noise model): chi^2 {:.1f} -> {:.1f}.",
      best->label(), best->effects.size() == 1 ? "it" : "them", diagnosis.n_data, best->chi2_before,
      best->chi2_after));
  return out;
}

}  // namespace chutelab::api
