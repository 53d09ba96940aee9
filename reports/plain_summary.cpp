#include "reports/plain_summary.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fmt/format.h>

#include "core/message.h"

namespace chutelab::reports {
namespace {

using validation::QuantityMisfit;

std::string spaced(std::string s) {
  std::replace(s.begin(), s.end(), '_', ' ');
  return s;
}

std::string join_words(const std::vector<std::string>& parts) {
  if (parts.empty()) return {};
  if (parts.size() == 1) return parts[0];
  std::string o;
  for (std::size_t k = 0; k + 1 < parts.size(); ++k) o += (k ? ", " : "") + parts[k];
  return o + " and " + parts.back();
}

std::vector<QuantityMisfit> beyond(const std::vector<QuantityMisfit>& all) {
  std::vector<QuantityMisfit> out;
  for (const auto& m : all)
    if (m.beyond_noise) out.push_back(m);
  std::stable_sort(out.begin(), out.end(),
                   [](const QuantityMisfit& a, const QuantityMisfit& b) { return a.rms_normalised > b.rms_normalised; });
  return out;
}

std::string rms_text(const validation::ValidationResult& r) {
  if (auto z = r.combined_rms_normalised()) return fmt::format("{:.2f}", *z);
  return "—";
}

// One model's quantities beyond the noise, judged on its own values alone (the combined view
// judges each value by the first model that predicts it, so a model later in the list, such as
// the DEM next to the analytical models, is never heard there).
std::vector<QuantityMisfit> beyond_for(const validation::ValidationResult& r, const std::string& model) {
  validation::ValidationResult own;
  for (const auto& c : r.comparisons)
    if (c.model == model) own.comparisons.push_back(c);
  return beyond(validation::quantity_misfits(own));
}

std::string short_effects(const std::vector<EffectDescription>& effects) {
  std::vector<std::string> s;
  for (const auto& e : effects) s.push_back(spaced(e.name));
  return join_words(s);
}

// Every effect added is a corrected record, not physics.
bool all_records(const std::vector<EffectDescription>& effects) {
  return !effects.empty() &&
         std::all_of(effects.begin(), effects.end(), [](const EffectDescription& e) { return e.record; });
}

std::string record_checks(const std::vector<EffectDescription>& effects) {
  std::vector<std::string> s;
  for (const auto& e : effects)
    if (!e.check.empty()) s.push_back(e.check);
  return join_words(s);
}

}  // namespace

// A hint is a command the reader pastes into a shell and runs as printed: the command line's
// spelling whichever front end wrote the report, the dataset as it was given, a word the shell would
// split or expand quoted.
std::string shell_word(const std::string& s) {
  // A control or invisible character never reaches the terminal (core/message.h): such a name is
  // shown escaped, which a shell would not take as it is.
  if (one_line(s) != s) return shown(s);
  if (!s.empty() && s.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-./=,:+@%") ==
                        std::string::npos)
    return s;
  std::string o = "'";
  for (char c : s) o += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return o + "'";
}

namespace {

std::string dataset_arg(const ReportInput& in) {
  return "--dataset " + shell_word(in.dataset->dir.empty() ? std::string(".") : in.dataset->dir.string());
}

// A new folder for the hinted run, named after the dataset and what it adds.
std::string out_arg(const ReportInput& in, std::string_view what) {
  std::filesystem::path dir = in.dataset->dir;
  std::string name = dir.filename().string();
  if (name.empty() || name == ".") name = dir.parent_path().filename().string();
  if (name.empty() || name == "." || name == "..") name = "dataset";
  return "--out " + shell_word(fmt::format("out/{}-{}", name, what));
}

// "chutelab estimate --dataset D --condition V4-28 --effect air_drag=0.752": the condition with the
// effects added, as estimate takes them.
std::string estimate_command(const ReportInput& in, const std::string& condition) {
  std::string c = fmt::format("chutelab estimate {} --condition {}", dataset_arg(in), shell_word(condition));
  for (const auto& e : in.effects) c += " --effect " + shell_word(fmt::format("{}={:.3g}", e.name, e.value));
  return c;
}

}  // namespace

std::string validate_command(const ReportInput& in, std::string_view flag, std::string_view what) {
  return fmt::format("chutelab validate {} {} {}", dataset_arg(in), flag, out_arg(in, what));
}

std::string effect_words(const EffectDescription& e, bool brief) {
  std::string v = fmt::format("{:.3g}", e.value);
  if (e.uncertainty) v += fmt::format(" ± {:.2g}", *e.uncertainty);
  if (!e.unit.empty()) v += " " + e.unit;
  return fmt::format("{} ({} {}{})", spaced(e.name), spaced(e.parameter), v,
                     e.fitted ? (brief ? ", fitted" : ", fitted to these measurements") : (brief ? "" : ", as given"));
}

std::string condition_words(const validation::Dataset& d, const std::string& condition) {
  const Station* s = d.station(condition);
  if (!s) return condition;
  return fmt::format("{} ({:.3g} m/s, {:.3g} t/h)", condition, s->belt_speed, s->mass_flow * 3.6);
}

std::vector<std::string> misfit_lines(const ReportInput& in, std::size_t max) {
  const auto before_all = validation::quantity_misfits(*in.baseline);
  const auto after_all = in.with_effects ? validation::quantity_misfits(*in.with_effects)
                                         : std::vector<QuantityMisfit>{};
  std::vector<QuantityMisfit> shown = beyond(before_all);
  for (const auto& a : beyond(after_all))
    if (!validation::find_misfit(shown, a.quantity))
      if (auto b = validation::find_misfit(before_all, a.quantity)) shown.push_back(*b);
  std::vector<std::array<std::string, 3>> rows;
  for (std::size_t k = 0; k < shown.size() && k < max; ++k) {
    const auto& m = shown[k];
    std::array<std::string, 3> row;
    // A stream boundary's label says which one; its symbol (y_upper) adds nothing.
    row[0] = m.quantity.starts_with("trajectory_") ? m.label : fmt::format("{} {}", m.label, m.symbol);
    while (!row[0].empty() && row[0].back() == ' ') row[0].pop_back();
    row[1] = m.model;
    if (in.with_effects) {
      const auto a = validation::find_misfit(after_all, m.quantity);
      row[2] = fmt::format("{} -> {} on average", validation::signed_amount(m, m.mean_error),
                           a ? validation::signed_amount(*a, a->mean_error) : std::string("—"));
      if (a && a->beyond_noise) row[2] += " (still beyond the uncertainties)";
    } else {
      row[2] = fmt::format("{} on average, {} at {}", validation::signed_amount(m, m.mean_error),
                           validation::signed_amount(m, m.worst_error), condition_words(*in.dataset, m.worst_condition));
    }
    rows.push_back(std::move(row));
  }
  std::size_t w0 = 0, w1 = 0;
  for (const auto& r : rows) {
    w0 = std::max(w0, r[0].size());
    w1 = std::max(w1, r[1].size());
  }
  std::vector<std::string> out;
  for (const auto& r : rows)
    out.push_back(fmt::format("  {:<{}}  {:<{}}  {}", r[0], w0, r[1], w1, r[2]));
  if (shown.size() > max) out.push_back(fmt::format("  ... and {} more quantities (report: \"Where the models fail\")",
                                                    shown.size() - max));
  return out;
}

std::vector<std::string> in_short(const ReportInput& in) {
  std::vector<std::string> out;
  const auto before_all = validation::quantity_misfits(*in.baseline);
  const auto bad = beyond(before_all);
  const validation::EffectFit* best = in.diagnosis ? in.diagnosis->best() : nullptr;

  // 1. The models as they are: each model judged on its own values too, so that one that agrees
  // (or one that does not) is named even where the combined view hears another model.
  std::vector<std::string> agreeing, missing;
  std::vector<QuantityMisfit> own_bad;
  std::string agreeing_rms, agreeing_one;
  for (const auto& m : in.baseline->models) {
    const auto z = in.baseline->overall_rms_normalised(m);
    if (!z) continue;
    const auto b = beyond_for(*in.baseline, m);
    if (b.empty()) {
      agreeing.push_back(m);
      agreeing_rms += fmt::format("{}{} {:.2f}", agreeing_rms.empty() ? "" : ", ", m, *z);
      agreeing_one = fmt::format("{:.2f}", *z);
    } else {
      missing.push_back(m);
      if (own_bad.empty()) own_bad = b;
    }
  }
  if (missing.empty()) {
    out.push_back(fmt::format("As they are, the models agree with the measurements within the stated uncertainties "
                              "(RMS E/u_val {}; 1 is the noise level).",
                              rms_text(*in.baseline)));
  } else {
    // The combined view when it sees the misfit; else the first model that misses on its own.
    const bool combined = !bad.empty();
    const auto& shown = combined ? bad : own_bad;
    std::string who = "the models";
    if (!agreeing.empty()) {
      out.push_back(fmt::format("{} {} with the measurements within the stated uncertainties (RMS E/u_val {}).",
                                join_words(agreeing), agreeing.size() == 1 ? "agrees" : "agree",
                                agreeing.size() == 1 ? agreeing_one : agreeing_rms));
      who = join_words(missing);
    }
    if (!combined) who = shown.front().model;
    std::vector<std::string> parts;
    for (std::size_t k = 0; k < shown.size() && k < 3; ++k)
      parts.push_back(fmt::format("the {} {}", shown[k].label, validation::amount_words(shown[k], shown[k].mean_error)));
    const auto& w = shown.front();
    const auto rms = combined ? rms_text(*in.baseline)
                              : fmt::format("{:.2f}", in.baseline->overall_rms_normalised(w.model).value_or(0.0));
    const bool plural = who == "the models" || (combined && missing.size() > 1);
    out.push_back(fmt::format("As {}, {} {} {} on average; the worst is the {} at {}, {} "
                              "(RMS E/u_val {}, where 1 is the noise level).",
                              plural ? "they are" : "it is", who, plural ? "put" : "puts", join_words(parts), w.label,
                              condition_words(*in.dataset, w.worst_condition),
                              validation::amount_words(w, w.worst_error), rms));
  }

  // 2. What the effect (or the diagnosis) says.
  std::vector<QuantityMisfit> left;
  if (in.with_effects && !in.effects.empty()) {
    left = beyond(validation::quantity_misfits(*in.with_effects));
    std::vector<std::string> added;
    for (const auto& e : in.effects) added.push_back(effect_words(e));
    std::string result;
    if (left.empty()) {
      result = "brings every quantity within its measurement uncertainty";
    } else {
      std::vector<std::string> parts;
      for (std::size_t k = 0; k < left.size() && k < 2; ++k)
        parts.push_back(fmt::format("the {} {}", left[k].label, validation::amount_words(left[k], left[k].mean_error)));
      result = "still leaves " + join_words(parts);
    }
    out.push_back(fmt::format("{} {} {} (RMS E/u_val {} -> {}).",
                              all_records(in.effects) ? "Correcting the recorded" : "Adding", join_words(added), result,
                              rms_text(*in.baseline), rms_text(*in.with_effects)));
  } else if (best && !bad.empty()) {
    std::vector<std::string> named;
    for (std::size_t i = 0; i < best->effects.size(); ++i)
      named.push_back(i < best->estimate.size() && i < best->parameters.size()
                          ? fmt::format("{} ({} {:.3g})", spaced(best->effects[i]), spaced(best->parameters[i]),
                                        best->estimate[i])
                          : spaced(best->effects[i]));
    out.push_back(fmt::format("The measurements point to {} as what the models miss; to see the models with it: {}.",
                              join_words(named), validate_command(in, "--add-missing", "add-missing")));
  } else if (in.diagnosis && !bad.empty()) {
    out.push_back("No effect in chutelab's library explains this misfit well; \"What is missing\" in the report "
                  "shows where it lies.");
  }

  // 3. What to do.
  // The acceptance judges the models as delivered (api/validate.h), whatever was added beside them.
  const auto& judged = in.accepted();
  if (judged.acceptance_checked && judged.acceptance_failed)
    out.push_back(fmt::format("Acceptance failed{}: {} of {} checked values are outside their tolerance (listed "
                              "under \"Outside tolerance\").",
                              !in.with_effects             ? ""
                              : in.accepted_with_effects ? " for the models with the effects"
                                                         : " for the models as delivered",
                              judged.failed_count(), judged.checked_count()));
  if (in.with_effects && !in.effects.empty() && best && !effect_choice_warning(in).empty()) {
    out.push_back(fmt::format("The measurements point to {} instead; to see the models with it: {}.",
                              spaced(best->label()), validate_command(in, "--add-missing", "add-missing")));
  } else if (in.with_effects && !in.effects.empty() && !bad.empty()) {
    const auto& w = bad.front();
    if (left.empty() && all_records(in.effects))
      out.push_back(fmt::format("Check the rig's record before changing any model: measure the {} ({}) and correct "
                                "the dataset; until then, predict with the corrected value ({}): "
                                "with the record as it is, the models put the {} up to {}.",
                                short_effects(in.effects), record_checks(in.effects),
                                estimate_command(in, w.worst_condition), w.label,
                                validation::amount_words(w, w.worst_error)));
    else if (left.empty())
      out.push_back(fmt::format("For this rig and material, predict with {} included ({}): without "
                                "it the models put the {} up to {}.",
                                short_effects(in.effects), estimate_command(in, w.worst_condition), w.label,
                                validation::amount_words(w, w.worst_error)));
    else
      out.push_back(fmt::format("Use the models' {} with care on this rig: even with {} it is off by more than the "
                                "measurements' uncertainty.",
                                left.front().label, short_effects(in.effects)));
  } else if (!in.diagnosis && !bad.empty()) {
    out.push_back(fmt::format("To see which physical effect would explain it: {}.",
                              validate_command(in, "--diagnose", "diagnosis")));
  }
  return out;
}

std::string effect_choice_warning(const ReportInput& in) {
  if (!in.diagnosis || !in.with_effects || in.effects.empty()) return {};
  std::vector<std::string> added;
  for (const auto& e : in.effects) added.push_back(e.name);
  const validation::EffectFit* best = in.diagnosis->best();
  if (!best)
    return fmt::format("The diagnosis finds no significant missing effect in these measurements; {} was added anyway, "
                       "so its fitted value may describe noise.",
                       join_words(added));
  std::vector<std::string> wanted = best->effects;
  std::vector<std::string> a = added;
  std::sort(wanted.begin(), wanted.end());
  std::sort(a.begin(), a.end());
  if (a == wanted) return {};
  // How much of the misfit the added one explains, when it was a single candidate.
  std::string share;
  if (added.size() == 1)
    for (const auto& f : in.diagnosis->singles)
      if (f.effects.size() == 1 && f.effects.front() == added.front())
        share = fmt::format(" (it explains {:.0f} % of the misfit, {} explains {:.0f} %)", 100.0 * f.explained_fraction,
                            best->label(), 100.0 * best->explained_fraction);
  return fmt::format("The measurements point to {}, not to {}{}: the error may fall for the wrong reason.",
                     best->label(), join_words(added), share);
}

}  // namespace chutelab::reports
