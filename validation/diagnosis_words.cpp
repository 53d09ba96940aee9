// The sentences of a diagnosis, rendered from its numbers and codes (validation/diagnosis.h): the
// physics first, in the quantities' own units and %, and the statistics after it as the evidence.
#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <map>

#include "core/markup.h"
#include "effects/at_condition.h"
#include "effects/registry.h"
#include "validation/diagnosis.h"
#include "validation/output_files.h"

namespace chutelab::validation {
namespace {

std::string quantity_words(const std::string& q) {
  if (auto parsed = parse_quantity(q)) return fmt::format("{} ({})", info(*parsed).label, info(*parsed).symbol);
  if (q.rfind("trajectory_", 0) == 0) {
    const std::string b = q.substr(11, q.find("_y_mm") - 11);
    return fmt::format("{} stream limit", b == "centre" ? "centre of the" : b);
  }
  return q;
}

std::string symbol_of(const std::string& q) {
  if (auto parsed = parse_quantity(q)) return std::string(info(*parsed).symbol);
  return quantity_words(q);
}

std::string value_with_unit(double v, double sd, const std::string& unit) {
  const std::string u = unit.empty() ? "" : " " + unit;
  if (!std::isfinite(sd)) return fmt::format("{:.4g}{} (unconstrained)", v, u);
  return fmt::format("{:.4g} ± {:.2g}{}", v, sd, u);
}

bool is_record(const std::string& candidate) {
  const auto* e = effects::find_candidate(candidate);
  return e && e->kind == effects::EffectInfo::Kind::record;
}

// A physical effect with its strength: "air_drag (drag_coefficient = 0.752 ± 0.031)".
std::string effect_words(const EffectFit& f, std::size_t i) {
  const auto* e = effects::find_candidate(f.effects[i]);
  return fmt::format("{} ({} = {})", f.effects[i], e ? e->parameter : f.parameters[i],
                     value_with_unit(f.estimate[i], f.uncertainty[i], e ? e->unit : ""));
}

// A recorded input's fitted error in words: "the plate distance is 25 ± 2 mm more than recorded
// (2.5 times its plausible error of 10 mm, the documented default for this input: more than a
// tolerance)"; a record wrong at one condition says where: "at V4-41 alone, the plate distance ...".
std::string record_words(const EffectFit& f, std::size_t i) {
  const auto* e = effects::find_candidate(f.effects[i]);
  const auto [input, condition] = effects::split_condition(f.effects[i]);
  // A fraction reads as %.
  const double scale = e->unit.empty() ? 100.0 : 1.0;
  const std::string unit = e->unit.empty() ? "%" : e->unit;
  const double v = f.estimate[i] * scale, sd = f.uncertainty[i] * scale;
  std::string name = input == "mass_flow_bias" ? "mass flow" : input;
  std::replace(name.begin(), name.end(), '_', ' ');
  const bool relative = unit == "%";
  std::string s = fmt::format("{}the {} is {} {} than recorded", condition.empty() ? "" : "at " + condition + " alone, ",
                              name,
                              std::isfinite(sd) ? fmt::format("{:.3g} ± {:.2g} {}", std::abs(v), sd, unit)
                                                : fmt::format("{:.3g} {} (unconstrained)", std::abs(v), unit),
                              relative ? (v >= 0 ? "higher" : "lower") : (v >= 0 ? "more" : "less"));
  if (i < f.prior_width.size() && f.prior_width[i] > 0.0) {
    const double w = f.prior_width[i] * scale, ratio = std::abs(v) / w;
    s += fmt::format(" ({:.1f} times its {} of {:.3g} {}: {})", ratio,
                     f.prior_stated[i] ? "stated uncertainty" : "plausible error (the documented default)", w, unit,
                     ratio >= 10.0  ? "a wrong entry or a changed rig rather than a tolerance"
                     : ratio >= 3.0 ? "more than a tolerance"
                     : ratio >= 1.0 ? "beyond its tolerance, though not far: a difference in the models of this "
                                      "size could look the same"
                                    : "within its tolerance, so the record may be right and this a difference in "
                                      "the models");
  }
  return s;
}

// An explanation's label in words, as the verdict names causes: "air_drag + plate_distance@V4-41" ->
// "air drag and the plate distance record at V4-41 alone".
std::string explanation_words(const std::string& label) {
  std::vector<std::string> parts;
  for (std::size_t from = 0; from <= label.size();) {
    const auto to = std::min(label.find(" + ", from), label.size());
    const auto [input, condition] = effects::split_condition(label.substr(from, to - from));
    std::string name = input == "mass_flow_bias" ? "mass flow" : input;
    std::replace(name.begin(), name.end(), '_', ' ');
    const auto* e = effects::find(input);
    parts.push_back(e && e->kind == effects::EffectInfo::Kind::record
                        ? "the " + name + " record" + (condition.empty() ? "" : " at " + condition + " alone")
                        : name);
    from = to + 3;
  }
  return fmt::format("{}", fmt::join(parts, " and "));
}

std::string record_words(const EffectFit& f) {
  std::vector<std::string> parts;
  for (std::size_t i = 0; i < f.effects.size(); ++i) parts.push_back(record_words(f, i));
  return fmt::format("{}", fmt::join(parts, ", and "));
}

// Every cause of an explanation, physics and records alike.
std::string fitted_words(const EffectFit& f) {
  if (f.effects.size() == 1) return is_record(f.effects[0]) ? "a wrong record (" + record_words(f, 0) + ")" : effect_words(f, 0);
  std::vector<std::string> parts;
  for (std::size_t i = 0; i < f.effects.size(); ++i)
    parts.push_back(is_record(f.effects[i]) ? "a wrong record: " + record_words(f, i)
                                            : "missing physics: " + effect_words(f, i));
  return fmt::format("{}", fmt::join(parts, "; "));
}

std::string record_checks(const EffectFit& f) {
  std::vector<std::string> c;
  for (const auto& n : f.effects)
    if (const auto* e = effects::find_candidate(n); e && !e->check.empty()) c.push_back(e->check);
  return c.empty() ? "" : fmt::format(" Check it: {}.", fmt::join(c, "; "));
}

// How far the models are off for one quantity, in its units: "R_n 6.1 % high", "the impact point 14 mm low".
std::string off_words(const QuantityShift& q, bool after) {
  const double v = after ? q.after : q.before, rel = after ? q.after_relative : q.before_relative;
  if (q.relative) return fmt::format("{} {:.1f} % {}", q.symbol, std::abs(100.0 * rel), rel >= 0 ? "high" : "low");
  return fmt::format("the {} {:.1f} {} {}", q.label, std::abs(v), q.unit, v >= 0 ? "high" : "low");
}

// The quantities the models as they are miss most, in units (at most three), largest first by the
// share of the misfit their mean error makes.
std::vector<const QuantityShift*> largest_shifts(const DiagnosisResult& r) {
  std::vector<const QuantityShift*> v;
  for (const auto& q : r.shifts_condition.empty() ? r.shifts : r.shifts_there) {
    bool discrepant = false;  // said apart, as a quantity no model explains
    for (const auto& d : r.model_form) discrepant = discrepant || d.quantity == q.quantity;
    if (!discrepant) v.push_back(&q);
  }
  auto size = [](const QuantityShift* q) {
    return q->relative ? std::abs(q->before_relative) * 100.0 : std::abs(q->before) / 2.0;
  };
  std::sort(v.begin(), v.end(), [&](auto* a, auto* b) { return size(a) > size(b); });
  std::erase_if(v, [&](auto* q) { return size(q) < 0.5; });  // below 0.5 % or 1 mm: not worth a word
  if (v.size() > 3) v.resize(3);
  return v;
}

std::string physics_words(const DiagnosisResult& r, const char* with_what) {
  const auto top = largest_shifts(r);
  if (top.empty()) return "";
  std::vector<std::string> before, after;
  for (const auto* q : top) before.push_back(off_words(*q, false)), after.push_back(off_words(*q, true));
  return fmt::format(" {} models as they are put {}; {} {}.",
                     r.shifts_condition.empty() ? "The" : "At " + r.shifts_condition + " the", fmt::join(before, ", "), with_what,
                     fmt::join(after, ", "));
}

std::string evidence_words(const EffectFit& f, int n) {
  return fmt::format("chi^2 {:.1f} -> {:.1f} for {} data ({:.0f} % of the misfit beyond noise removed), "
                     "delta BIC {:.1f}, p (adjusted for the candidates tried) {:.2g}.",
                     f.chi2_before, f.chi2_after, n, 100 * f.explained_fraction, f.delta_bic, f.p_adjusted) +
         (f.prior_penalty > 0.0 ? fmt::format(" The record's implausibility is charged {:.1f} in chi^2 before the "
                                              "test (a Cauchy prior of the plausible error's width).",
                                              f.prior_penalty)
                                : "");
}

std::string leftover_words(const Leftover& l) {
  if (l.quantity == "all") return "the whole scatter is larger than the uncertainties allow, evenly";
  const std::string mean = parse_quantity(l.quantity) && info(*parse_quantity(l.quantity)).unit != "mm"
                               ? fmt::format("{:+.1f} % on average", 100 * l.mean_relative)
                               : fmt::format("{:+.1f} mm on average", l.mean_error);
  const std::string how = l.pattern == "bias"      ? "a steady bias"
                          : l.pattern == "scatter" ? "more scatter than the uncertainties allow"
                                                   : "a trend with the " + l.pattern;
  return fmt::format("{} ({}): {}, {}", quantity_words(l.quantity), l.model, how, mean);
}

std::string out_of_range_words(const EffectFit& f) {
  const auto* e = effects::find_candidate(f.effects[0]);
  const auto& u = *f.unbounded;
  const bool below = u.estimate < e->lower;
  return fmt::format("{} would need {} = {}, {} its physical range [{:g}, {:g}]{}", f.effects[0], e->parameter,
                     value_with_unit(u.estimate, u.uncertainty, e->unit), below ? "below" : "above", e->lower,
                     e->upper, below && e->lower == e->neutral ? ": the data ask for the opposite of this effect, which "
                                                                 "no physics of it gives"
                                                               : "");
}

std::string scale_words(const ScaleFinding& s) {
  if (s.applied)
    return fmt::format("The readings scatter {:.1f} times more than their stated uncertainties say (chi^2/dof over "
                       "{} degrees of freedom, p = {:.2g}): the stated uncertainties look too small, so every "
                       "uncertainty was widened by this factor (Birge ratio) for the fits, their ± and the tests.",
                       s.factor, s.dof, s.p_high);
  if (s.too_large)
    return fmt::format("The readings scatter only {:.2f} times their stated uncertainties (p = {:.2g} that honest "
                       "uncertainties scatter this little): the stated uncertainties look about {:.1f} times too "
                       "large; they were not narrowed, so the ± and tests here are conservative.",
                       s.factor, s.p_low, 1.0 / std::max(s.factor, 1e-3));
  return "";
}

// A named cause whose strength the data want to change with an operating variable, in its terms.
std::string shape_words(const ShapeFinding& f) {
  const std::string unit = f.unit.empty() ? "" : " " + f.unit;
  std::string s = fmt::format(
      "The data want {}'s {} to change with {}: about {:.3g}{} at {:.3g} {} and {:.3g}{} at {:.3g} {} (as {}^{:.2f} ± "
      "{:.2f}), where the library's form keeps it the same at every condition; the {} fitted is a compromise "
      "between conditions",
      f.effect, f.parameter, f.driver, f.low_strength, unit, f.low_driver, f.driver_unit, f.high_strength, unit,
      f.high_driver, f.driver_unit, f.driver, f.exponent, f.exponent_uncertainty, f.parameter);
  if (!f.grows.empty()) {
    const double p = f.power + f.exponent;
    auto power_words = [](double x) -> std::string {
      if (std::abs(x - 1.0) < 0.25) return "about linearly with it";
      if (std::abs(x - 2.0) < 0.25) return "about with its square";
      if (std::abs(x) < 0.25) return "hardly at all with it";
      return fmt::format("about as its power {:.1f}", x);
    };
    s += fmt::format(": {} the data want grows {} rather than {} (the library's form)", f.grows, power_words(p),
                     f.power == 2.0 ? "with its square" : fmt::format("as its power {:g}", f.power));
  }
  return s;
}

// In the quantity's own terms (its unit, and % for forces and speeds): the statistics behind it (mean
// and RMS of E/u, the correlation) are in the table under these lines.
void describe_failures(DiagnosisResult& r) {
  r.failure_summary.clear();
  for (std::size_t i = 0; i + 3 < r.patterns.size(); i += 4) {
    const auto& p = r.patterns[i];
    const bool bias = std::abs(p.mean_normalised) > 3.0 / std::sqrt(std::max(p.n, 1));
    if (p.rms_normalised <= 2.0 && !bias) continue;
    // The shifts follow the misfit's groups (one per model and quantity), as the patterns do.
    const QuantityShift* q = i / 4 < r.shifts.size() && r.shifts[i / 4].quantity == p.quantity ? &r.shifts[i / 4] : nullptr;
    std::string s = fmt::format("{}: {} ", quantity_words(p.quantity), p.model);
    if (bias) {
      std::string by = "beyond its uncertainties";
      if (q && q->relative)
        by = fmt::format("by {:.1f} % ({:.3g} {})", std::abs(100.0 * q->before_relative), std::abs(q->before), q->unit);
      else if (q)
        by = fmt::format("by {:.1f} {}", std::abs(q->before), q->unit);
      s += fmt::format("{} it {} on average", p.mean_normalised > 0 ? "over-predicts" : "under-predicts", by);
    } else {
      s += fmt::format("misses it without a steady bias, scattering {:.1f} times as far as the uncertainties allow",
                       p.rms_normalised);
    }
    const ResidualPattern* strongest = nullptr;
    for (std::size_t k = i; k < i + 4; ++k)
      if (!strongest || std::abs(r.patterns[k].correlation) > std::abs(strongest->correlation)) strongest = &r.patterns[k];
    if (p.n >= 3 && std::abs(strongest->correlation) >= 0.7) {
      // Residual = prediction - measurement: a positive trend means over-prediction grows.
      const bool grows = (strongest->correlation > 0) == (p.mean_normalised >= 0);
      s += fmt::format("; the misfit {} {}with {}", grows ? "grows" : "shrinks",
                       std::abs(strongest->correlation) >= 0.9 ? "steadily " : "", strongest->driver);
    }
    r.failure_summary.push_back(s + ".");
  }
}

void describe_findings(DiagnosisResult& r, const DiagnoseOptions& opt) {
  r.findings.clear();
  for (const auto& o : r.outliers) {
    std::string text = fmt::format(
        "Check this reading: {} {} ({}:{}) reads {:.4g}, {:.0f} % {} what the best explanation predicts "
        "({:.4g}; {:.1f} scatter widths off, {:.1f} under the closest candidate). It was left out of every fit.",
        o.condition, symbol_of(o.quantity), o.where.file, o.where.line, o.measured,
        std::abs(100 * o.relative), o.relative >= 0 ? "above" : "below", o.predicted, std::abs(o.deviation),
        o.closest);
    // One reading cannot tell a wrong reading from a record wrong at its condition alone.
    if (!o.records.empty()) {
      std::vector<std::string> which;
      for (const auto& f : o.records) which.push_back(record_words(f, 0));
      text += fmt::format(" If the reading is right, the record is wrong there instead: {}; the condition's other "
                          "readings agree with {}, so only a check tells.{}",
                          fmt::join(which, ", or "), o.records.size() > 1 ? "each" : "either",
                          record_checks(o.records.front()));
    }
    r.findings.push_back(std::move(text));
  }
  for (const auto& i : r.influential)
    r.findings.push_back(fmt::format("One reading moves the fitted strength: without {} {} ({}:{}) {} moves by {:+.1f} "
                                     "sd. It is plausible, so it stays; check it.",
                                     i.condition, symbol_of(i.quantity), i.where.file, i.where.line, i.parameter,
                                     i.shift_sd));
  for (const auto& d : r.model_form) {
    const bool rel = parse_quantity(d.quantity) && info(*parse_quantity(d.quantity)).unit != "mm";
    r.findings.push_back(fmt::format(
        "No model explains {} as {} predicts it: it is {} at {} readings even with the best explanation. It was "
        "given a model discrepancy of ±{:.3g} {} (a variance added to its uncertainties), so that the other "
        "quantities decide which effect is missing.",
        quantity_words(d.quantity), d.model,
        rel ? fmt::format("{:.1f} % {} on average", std::abs(100 * d.mean_relative), d.mean_relative >= 0 ? "high" : "low")
            : fmt::format("{:.1f} mm {} on average", std::abs(d.mean_error), d.mean_error >= 0 ? "high" : "low"),
        d.n, d.tau, parse_quantity(d.quantity) ? std::string(info(*parse_quantity(d.quantity)).unit) : "mm"));
  }
  if (const auto& c = r.concentrated) {
    const auto* e = effects::find_candidate(c->effect);
    r.findings.push_back(fmt::format(
        "{} rests on {} alone ({:.0f} % of its evidence): an error in how {} predicts that quantity would look the "
        "same. Confirm it independently{}.",
        c->effect, quantity_words(c->quantity), 100 * c->share, c->model,
        e && !e->check.empty() ? fmt::format(" ({})", e->check) : ""));
  }
  if (const auto& rs = r.record_scope) {
    const double scale = rs->unit.empty() ? 100.0 : 1.0;
    const std::string unit = rs->unit.empty() ? "%" : rs->unit;
    std::string name = rs->input;
    std::replace(name.begin(), name.end(), '_', ' ');
    std::vector<std::string> per;
    for (std::size_t c = 0; c < rs->conditions.size(); ++c)
      per.push_back(fmt::format("{} {:+.3g} ± {:.2g} {}", rs->conditions[c], rs->estimate[c] * scale,
                                rs->uncertainty[c] * scale, unit));
    if (rs->differs)
      r.findings.push_back(fmt::format(
          "The {} error differs between conditions (p = {:.2g} that one error for the rig fits as well; chi^2 {:.1f} "
          "-> {:.1f} with one per condition): {}. The rig changed between tests, not only its drawing.",
          name, rs->p, rs->rig_wide_chi2, rs->per_condition_chi2, fmt::join(per, ", ")));
    else
      r.findings.push_back(fmt::format(
          "The {} error is the same at every condition within the noise (p = {:.2g} for one error per condition "
          "against one for the rig): a drawing or set-up error common to the whole rig.",
          name, rs->p));
  }
  if (!r.singles.empty() && r.singles.front().within_plausible_error() && r.singles.front().p_adjusted < opt.alpha)
    r.findings.push_back(fmt::format(
        "The data pin a recorded input closer than its record claims: {}. Within its plausible error, so the record "
        "is right to within its tolerance and is not called wrong (the fit improves chi^2 from {:.1f} to {:.1f}; a "
        "model-form difference smaller than the record's tolerance can look like this).",
        record_words(r.singles.front()), r.singles.front().chi2_before, r.singles.front().chi2_after));
  if (const auto s = scale_words(r.scale); !s.empty()) r.findings.push_back(s);
  if (r.thin_data)
    r.findings.push_back(fmt::format(
        "Thin data: {} condition{} and {} measured quantit{} ({} values). Effects that act alike cannot be told "
        "apart on so few; measure more belt speeds or flows before trusting which effect is named.",
        r.n_conditions, r.n_conditions == 1 ? "" : "s", r.n_quantities, r.n_quantities == 1 ? "y" : "ies", r.n_data));
  if (r.one_belt_speed || r.one_mass_flow)
    r.findings.push_back(fmt::format(
        "Every condition ran at one {}: effects that grow with it (air drag and belt slip with speed; the flow's "
        "own records with flow) look alike here, and a dependence on it cannot be seen. Measure at a second {} "
        "before trusting which of them is named.",
        r.one_belt_speed && r.one_mass_flow ? "belt speed and one mass flow" : r.one_belt_speed ? "belt speed" : "mass flow",
        r.one_belt_speed ? "belt speed" : "flow"));
}

std::string discriminator_words(const Discriminator& d) {
  if (d.quantity.empty())
    return fmt::format("{} and {}: no quantity in chutelab's vocabulary separates them by even one uncertainty at "
                       "these conditions; test other belt speeds or drop heights",
                       d.a, d.b);
  return fmt::format("{} vs {}: measure {} at {} ({}): {} predicts {:.3g} {}, {} predicts {:.3g} {} ({:.1f} "
                     "uncertainties apart){}",
                     d.a, d.b, d.quantity, d.condition, d.model == "proportional" ? "any model" : d.model, d.a,
                     d.value_a, d.unit, d.b, d.value_b, d.unit, d.separation,
                     d.measured_here ? "" : "; not measured in this dataset");
}

void describe_ties(DiagnosisResult& r) {
  r.discriminators.clear();
  r.proportional.clear();
  std::map<std::pair<std::string, std::string>, std::vector<const Discriminator*>> proportional;
  for (const auto& d : r.ties) {
    if (d.model == "proportional") proportional[{d.a, d.b}].push_back(&d);
    else r.discriminators.push_back(discriminator_words(d));
  }
  for (const auto& [pair, ds] : proportional) {
    std::vector<std::string> ways;
    for (const auto* d : ds)
      if (!d->quantity.empty())
        ways.push_back(fmt::format("{} (not measured here; {} predicts {:.3g} {}, {} {:.3g} {})", d->quantity, d->a,
                                   d->value_a, d->unit, d->b, d->value_b, d->unit));
    for (const auto& n : {pair.first, pair.second})
      if (const auto* i = effects::find_candidate(n); i && !i->check.empty())
        ways.push_back(fmt::format("for {}: {}", explanation_words(n), i->check));
    r.proportional.push_back(fmt::format(
        "{} and {} move every measured quantity in proportion (these data cannot tell them apart); to separate them, "
        "measure {}",
        explanation_words(pair.first), explanation_words(pair.second),
        ways.empty() ? "at other belt speeds or drop heights" : fmt::format("{}", fmt::join(ways, "; "))));
  }
}

std::string verdict_words(const DiagnosisResult& r) {
  const EffectFit* b = r.best();
  switch (r.verdict_code) {
    case Verdict::no_data:
      return "No measurement has an uncertainty, so nothing can be judged: state uncertainties in measurements.csv.";
    case Verdict::consistent:
    {
      // The words must agree with the numbers: "within the stated uncertainties" only where the
      // readings kept are within them by the test the verdict rests on.
      const std::size_t out = r.outliers.size();
      const std::string kept =
          out ? fmt::format(" once the {} reading{} named below {} left out", out, out == 1 ? "" : "s", out == 1 ? "is" : "are")
              : "";
      if (r.scale.applied)
        return fmt::format("No significant missing effect: the models explain the data within uncertainties {:.1f} "
                           "times the stated ones{} (the readings scatter more than stated, without a pattern any "
                           "candidate has).",
                           r.scale.factor, kept);
      if (r.kept_p_value >= r.alpha)
        return fmt::format("No significant missing effect: the models explain the data within the stated "
                           "uncertainties{}.",
                           kept);
      return fmt::format("No significant missing effect: no candidate explains the misfit{}, and it is small: the "
                         "readings scatter {:.2f} times their stated uncertainties, without a pattern in any quantity.",
                         kept, std::sqrt(r.chi2_kept / std::max(1, r.n_kept)));
    }
    case Verdict::missing_effect: {
      const bool one_condition = b->effects.size() == 1 && !effects::split_condition(b->effects[0]).second.empty();
      std::string v =
          b->effects.size() > 1
              ? fmt::format("{} causes together explain the data: {}.{}{}", b->effects.size() == 2 ? "Two" : "Three",
                            fitted_words(*b), physics_words(r, "with them what is left is noise:"), record_checks(*b))
          : b->is_record()
              ? fmt::format("The record looks wrong{}, not the physics: {}.{}{}", one_condition ? " at one condition" : "",
                            record_words(*b), physics_words(r, "with the corrected record what is left is noise:"),
                            record_checks(*b))
              : fmt::format("Missing effect: {}.{}", fitted_words(*b), physics_words(r, "with it what is left is noise:"));
      if (!r.indistinguishable.empty()) {
        std::vector<std::string> alike;
        for (const auto& l : r.indistinguishable) alike.push_back(explanation_words(l));
        v += fmt::format(" About as good: {}.", fmt::join(alike, "; "));
      }
      for (const auto& p : r.proportional) v += " But " + p + ".";
      return v;
    }
    case Verdict::partial_explanation: {
      std::vector<std::string> left;
      for (const auto& l : r.leftovers) left.push_back(leftover_words(l));
      for (const auto& f : r.shape) left.push_back(shape_words(f));
      bool edge = false;
      for (bool e : b->at_bound) edge = edge || e;
      const std::string who = b->effects.size() == 1 && b->is_record() ? "A wrong record (" + record_words(*b) + ")"
                                                                        : fitted_words(*b);
      std::string v = fmt::format("{} {} most of the misfit ({:.0f} % of it beyond noise), but {}.{}",
                                  b->effects.size() > 1 ? "Together, " + fitted_words(*b) + "," : who,
                                  b->effects.size() > 1 ? "explain" : "explains", 100 * b->explained_fraction,
                                  left.empty() ? "needs a strength at the edge of its physical range: it is probably "
                                                 "standing in for something else"
                                  : r.leftovers.empty() ? fmt::format("{}", fmt::join(left, "; "))
                                                        : fmt::format("the rest is not noise: {}", fmt::join(left, "; ")),
                                  physics_words(r, "with it"));
      return v;
    }
    case Verdict::out_of_range: {
      std::vector<std::string> parts;
      for (const auto& f : r.singles)
        if (f.unbounded && f.unbounded->wants_outside) parts.push_back(out_of_range_words(f));
      return fmt::format("No library effect explains the data within its physical range: {}.{} Look for physics "
                         "outside the library, or check the rig's record (geometry, speeds, flows).",
                         fmt::join(parts, "; "), physics_words(r, "such a strength would leave"));
    }
    case Verdict::outside_library: {
      std::vector<std::string> where;
      for (const auto& l : r.leftovers) where.push_back(leftover_words(l));
      for (const auto& d : r.model_form) where.push_back(quantity_words(d.quantity) + " (no model explains it)");
      return fmt::format("The models miss the data and no effect in the library explains it: look outside the "
                         "library (geometry, inputs, model form). Where: {}.{}",
                         fmt::join(where, "; "), physics_words(r, "").empty() ? "" : physics_words(r, "nothing changes:"));
    }
  }
  return "";
}

// The statistics behind the verdict, apart from its words.
std::string evidence_of(const DiagnosisResult& r) {
  if (r.verdict_code == Verdict::no_data) return "";
  if (const EffectFit* b = r.best()) return evidence_words(*b, r.n_data);
  return fmt::format("chi^2 of the models as they are {:.1f} for {} data (p = {:.2g} that honest noise gives this "
                     "much or more).",
                     r.chi2_baseline, r.n_data, r.baseline_p_value);
}

void describe_caveats(DiagnosisResult& r, const DiagnoseOptions& opt) {
  r.caveats.clear();
  for (const auto& [name, description] : r.exported_models)
    r.caveats.push_back(fmt::format(
        "{} is another code's exported results ({}): chutelab cannot re-run it, so every {} prediction with a "
        "candidate effect is its result plus the analytical models' response to the effect (DESIGN.md §5), "
        "including the recommended fit's, which no run confirms.",
        name, description, name));
  if (r.used_surrogate) {
    std::vector<std::string> own, cheap;
    for (const auto& f : r.singles) {
      if (f.signature == "own runs") own.push_back(f.label());
      if (f.signature == "analytical only") cheap.push_back(f.label());
    }
    if (!own.empty())
      r.caveats.push_back(fmt::format(
          "The expensive model's response to {} comes from its own runs, one per condition with the effect at a probe "
          "strength (twice its typical value) and the baseline's seed, carried to other strengths along the "
          "analytical models' response.",
          fmt::join(own, ", ")));
    if (!cheap.empty())
      r.caveats.push_back(fmt::format(
          "The expensive model cannot represent {}: their signatures are the analytical models' response applied as "
          "a difference (DESIGN.md §5), marked \"analytical only\" in the ranking.",
          fmt::join(cheap, ", ")));
    std::vector<std::string> rerun;
    for (const auto* list : {&r.singles, &r.pairs})
      for (const auto& f : *list)
        if (f.chi2_from_signatures)
          rerun.push_back(fmt::format("{} (chi^2 {:.1f} from the runs, {:.1f} from the signatures)", f.label(),
                                      f.chi2_after, *f.chi2_from_signatures));
    if (!rerun.empty())
      r.caveats.push_back(fmt::format(
          "The leading candidates were run for real at their fitted strengths, and they are ranked by those runs: {}.",
          fmt::join(rerun, "; ")));
    if (const EffectFit* b = r.best(); b && b->profile) {
      std::vector<std::string> pts;
      for (const auto& [v, c] : b->profile->points) pts.push_back(fmt::format("{:.4g}: {:.1f}", v, c));
      r.caveats.push_back(
          b->profile->bracketed
              ? fmt::format("{}'s strength and ± come from real runs at {} strengths (chi^2 {}), {}, not the "
                            "signature's linear response.{}",
                            b->label(), b->profile->points.size(), fmt::join(pts, ", "),
                            b->profile->points.size() >= 4
                                ? fmt::format("a least-squares parabola through them all: its vertex, and an sd from "
                                              "its curvature and the vertex's own uncertainty (the runs' chi^2 "
                                              "scatter {:.1f} about it)",
                                              b->profile->scatter)
                                : std::string("a parabola through the lowest three: its minimum and curvature"),
                            b->profile_widened > 1.0
                                ? fmt::format(" The ± is widened {:.1f} times: the readings scatter about the real "
                                              "runs more than their uncertainties say (the larger of the Birge ratio "
                                              "of the quantities that fix the strength and the sandwich estimate "
                                              "from the readings' own leave-one-out pulls).",
                                              b->profile_widened)
                                : "")
              : fmt::format("Real runs at {} strengths around {} (chi^2 {}) did not bracket a minimum: its strength "
                            "and ± are the signature's, which assume a linear response.",
                            b->profile->points.size(), b->label(), fmt::join(pts, ", ")));
    }
    if (r.confirmed_chi2 && r.best() && !r.best()->chi2_from_signatures)
      r.caveats.push_back(fmt::format("Confirmed by running the expensive model with {} on: chi^2 = {:.1f} (the "
                                      "estimate from differences was {:.1f}).",
                                      r.best()->label(), *r.confirmed_chi2, r.best()->chi2_after));
  }
  r.caveats.push_back(fmt::format(
      "Significance: likelihood-ratio test per candidate (an F test once the uncertainties are widened), "
      "Bonferroni-corrected over the {} candidates tried (family-wise false-alarm rate {:.0f} %). An explanation is "
      "named only when what it leaves has no bias, trend or excess scatter in any quantity at the same rate.",
      r.singles.size(), 100 * opt.alpha));
  // Fits outside a range that come close to the recommended explanation (a mimic far behind is no news).
  if (r.verdict_code != Verdict::out_of_range) {
    const EffectFit* b = r.best();
    std::vector<std::string> parts;
    for (const auto& f : r.singles)
      if (f.unbounded && f.unbounded->wants_outside &&
          (!b || f.unbounded->chi2 <= b->chi2_after + opt.tie_margin_bic))
        parts.push_back(out_of_range_words(f));
    if (!parts.empty())
      r.caveats.push_back(fmt::format("About as good, but outside their physical ranges: {}.", fmt::join(parts, "; ")));
  }
  if (r.noise_rounds > 1)
    r.caveats.push_back(fmt::format("The fits were repeated {} times until the outliers, discrepancies and "
                                    "uncertainty scale agreed with the explanation they were judged against.",
                                    r.noise_rounds));
  if (!r.unsteady_baseline.empty())
    r.caveats.push_back(fmt::format(
        "The baseline's steady means came from windows that some plate loads still moved through, at {}: the "
        "build-up on the plate was still forming. Their ± does not cover that, and an effect fitted to those loads "
        "(plate friction, for R_s) may stand in for it. --dem-steady-on all judges the window on every load "
        "(bench/WINDOW.md).",
        fmt::join(r.unsteady_baseline, "; ")));
  r.caveats.push_back("Only the effects in chutelab's library were tried; a misfit they cannot explain points to "
                      "physics outside it.");
  if (r.n_without_uncertainty > 0)
    r.caveats.push_back(fmt::format("{} measured values had no uncertainty or no prediction and were left out of chi^2.",
                                    r.n_without_uncertainty));
}

}  // namespace

void describe(DiagnosisResult& r, const DiagnoseOptions& opt) {
  describe_failures(r);
  describe_findings(r, opt);
  r.indistinguishable.erase(std::unique(r.indistinguishable.begin(), r.indistinguishable.end()),
                            r.indistinguishable.end());
  describe_ties(r);
  r.verdict = verdict_words(r);
  r.evidence = evidence_of(r);
  describe_caveats(r, opt);
}

std::string diagnosis_csv(const DiagnosisResult& r) {
  std::string o =
      "rank,effect,parameter,estimate,uncertainty,chi2_before,chi2_after,delta_bic,"
      "explained_fraction,significant,p_value,p_adjusted,signature,outside_range_estimate,outside_range_uncertainty,"
      "wants_outside_range,beaten_outside_range_by\n";
  auto row = [&](const EffectFit& f, const std::string& rank) {
    std::vector<std::string> est, unc;
    for (double v : f.estimate) est.push_back(csv_number(v));
    for (double v : f.uncertainty) unc.push_back(std::isfinite(v) ? csv_number(v) : "inf");
    const bool ub = f.unbounded.has_value();
    o += fmt::format("{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}\n", rank, fmt::join(f.effects, "+"),
                     fmt::join(f.parameters, "+"), fmt::join(est, "+"), fmt::join(unc, "+"),
                     csv_number(f.chi2_before), csv_number(f.chi2_after), csv_number(f.delta_bic),
                     csv_number(f.explained_fraction), f.significant ? "yes" : "no", csv_number(f.p_value),
                     csv_number(f.p_adjusted), f.signature, ub ? csv_number(f.unbounded->estimate) : "",
                     ub ? (std::isfinite(f.unbounded->uncertainty) ? csv_number(f.unbounded->uncertainty) : "inf") : "",
                     ub && f.unbounded->wants_outside ? "yes" : "no", f.beaten_outside_range_by);
  };
  for (const auto& f : r.singles) row(f, std::to_string(f.rank));
  for (const auto& f : r.pairs) row(f, "pair");
  return o;
}

std::string diagnosis_markdown(const DiagnosisResult& r) {
  // The setup's name is the user's text: a Markdown viewer renders HTML in it, so it goes in escaped.
  std::string o = fmt::format("# chutelab diagnosis: {}\n\n", markup_escape(r.dataset, Markup::html));
  o += fmt::format("**{}**\n\n", r.verdict);
  if (!r.evidence.empty()) o += fmt::format("How sure is this? {}\n\n", r.evidence);
  if (!r.findings.empty()) {
    o += "## What the data say about themselves\n\n";
    for (const auto& s : r.findings) o += "- " + s + "\n";
    o += "\n";
  }
  o += fmt::format("Models: {}; each measured value is compared with the first of them that predicts "
                   "it. {} data with uncertainties; chi^2 of the models as they are: {:.1f} (p = {:.2g}).\n\n",
                   fmt::join(r.models, ", "), r.n_data, r.chi2_baseline, r.baseline_p_value);
  o += "## Where the models fail\n\n";
  if (r.failure_summary.empty()) o += "Every quantity is within about two uncertainties of its measurement.\n";
  for (const auto& s : r.failure_summary) o += "- " + s + "\n";
  o += "\n| model | quantity | n | mean E/u | RMS E/u | r(belt speed) | r(mass flow) | r(flight time) | r(drop height) |\n";
  o += "|---|---|---|---|---|---|---|---|---|\n";
  for (std::size_t i = 0; i + 3 < r.patterns.size(); i += 4) {
    const auto& p = r.patterns[i];
    o += fmt::format("| {} | {} | {} | {:+.2f} | {:.2f} | {:+.2f} | {:+.2f} | {:+.2f} | {:+.2f} |\n", p.model,
                     p.quantity, p.n, p.mean_normalised, p.rms_normalised, r.patterns[i].correlation,
                     r.patterns[i + 1].correlation, r.patterns[i + 2].correlation, r.patterns[i + 3].correlation);
  }
  o += "\n## Candidate effects, ranked\n\n";
  const bool sig = r.used_surrogate;
  o += fmt::format("| rank | effect | estimate ± sd | chi^2 after | delta BIC | explained | p (adjusted) | significant "
                   "| outside its range |{}\n",
                   sig ? " signature |" : "");
  o += fmt::format("|---|---|---|---|---|---|---|---|---{}|\n", sig ? "|---" : "");
  auto est = [](const EffectFit& f) {
    std::vector<std::string> v;
    for (std::size_t i = 0; i < f.estimate.size(); ++i)
      v.push_back(fmt::format("{} = {:.4g} ± {}", f.parameters[i], f.estimate[i],
                              std::isfinite(f.uncertainty[i]) ? fmt::format("{:.2g}", f.uncertainty[i])
                                                              : std::string("unconstrained")));
    return fmt::format("{}", fmt::join(v, "; "));
  };
  auto outside = [](const EffectFit& f) -> std::string {
    if (!f.unbounded) return "";
    return fmt::format("{:.4g} ± {:.2g}{}", f.unbounded->estimate, f.unbounded->uncertainty,
                       f.unbounded->wants_outside ? " (wanted)" : "");
  };
  for (const auto& f : r.singles)
    o += fmt::format("| {} | {} | {} | {:.1f} | {:.1f} | {:.0f} % | {:.2g} | {} | {} |{}\n", f.rank, f.label(), est(f),
                     f.chi2_after, f.delta_bic, 100 * f.explained_fraction, f.p_adjusted,
                     f.significant ? (f.beaten_outside_range_by.empty() ? "yes" : "yes, beaten outside its range")
                                   : "no",
                     outside(f), sig ? " " + f.signature + " |" : "");
  if (!r.pairs.empty()) {
    o += "\nPairs that beat every single effect by a clear margin:\n\n";
    for (const auto& f : r.pairs)
      o += fmt::format("- {} ({}): chi^2 {:.1f}, delta BIC {:.1f}\n", f.label(), est(f), f.chi2_after, f.delta_bic);
  }
  if (!r.indistinguishable.empty() || !r.proportional.empty()) {
    o += "\n## Indistinguishable alternatives\n\n";
    for (const auto& s : r.proportional) o += "- " + s + "\n";
    for (const auto& s : r.discriminators) o += "- " + s + "\n";
  }
  o += "\n## Caveats\n\n";
  for (const auto& c : r.caveats) o += "- " + c + "\n";
  return o;
}

}  // namespace chutelab::validation
