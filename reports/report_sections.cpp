// The report's sections in the order they tell the story: what was compared and the verdict in
// words, where the models fail, the values outside tolerance, what an added effect changes and the
// diagnosis's evidence; then the detail (the reference study's tables and figures, trends, plate
// maps, findings, provenance, studies) and the V&V 20 appendix. assemble() is that list of steps.
#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <stdexcept>

#include "reports/common.h"
#include "reports/plain_summary.h"
#include "reports/report_doc.h"
#include "reports/studies.h"
#include "validation/failed_values.h"
#include "validation/quantity_misfit.h"

namespace chutelab::reports {
namespace {

using validation::ValidationResult;

std::string effects_label(const ValidationResult& r) {
  return r.effects.empty() ? std::string("(none)") : fmt::format("{}", fmt::join(r.effects, ", "));
}

struct Variant {
  const ValidationResult* result;
  std::string suffix;  // element ids: "base" / "effects"
  std::string title;   // "models as they are" / "with effects: ..."
};

std::vector<Variant> variants(const ReportInput& in) {
  std::vector<Variant> v{{in.baseline, "base", "Models as they are"}};
  if (in.with_effects) v.push_back({in.with_effects, "effects", "With effects: " + effects_label(*in.with_effects)});
  return v;
}

// What the effects change, quantity by quantity, in the quantity's unit or in per cent: the mean
// error and the worst one, before and after.
Table change_in_words(const validation::Dataset& d, const ValidationResult& before, const ValidationResult& after) {
  Table t;
  t.id = "change-in-words";
  t.caption = "What the effects change: mean and worst error per quantity";
  t.columns = {{"", "quantity", "", true},      {"", "judged by", "", true},   {"", "mean error before", "", false},
               {"", "mean error after", "", false}, {"", "worst before", "", true}, {"", "worst after", "", true}};
  const auto after_all = validation::quantity_misfits(after);
  for (const auto& b : validation::quantity_misfits(before)) {
    const auto a = validation::find_misfit(after_all, b.quantity);
    auto worst = [&](const validation::QuantityMisfit& m) {
      Cell c{fmt::format("{} at {}", validation::signed_amount(m, m.worst_error), condition_words(d, m.worst_condition)),
             "", false, "", true};
      c.beyond = std::abs(m.worst_normalised) > 2.0;
      return c;
    };
    Cell mb{validation::signed_amount(b, b.mean_error)}, ma{a ? validation::signed_amount(*a, a->mean_error)
                                                               : std::string(kDash)};
    mb.beyond = b.beyond_noise;
    ma.beyond = a && a->beyond_noise;
    t.rows.push_back({{b.label + (b.quantity.starts_with("trajectory_") ? "" : " " + b.symbol), "", false, "", true},
                      {b.model, "", false, "", true},
                      mb,
                      ma,
                      worst(b),
                      a ? worst(*a) : Cell{std::string(kDash)}});
  }
  t.notes.push_back("Error = predicted − measured, in per cent of the measured value for forces and speeds and in mm "
                    "for heights; each value judged by the first model that predicts it. Highlighted: more than the "
                    "stated uncertainties explain (a mean beyond the noise, a value beyond 2 u_val).");
  return t;
}

// Before/after: what was added, its physics, every E/u_val before and after, and how far the
// misfit fell. `described`: effects whose physics the page already shows (the recommended one).
void before_after(Doc& d, const Context& c, const std::vector<std::string>& described = {}) {
  const ReportInput& in = c.in;
  if (!in.with_effects) return;
  std::vector<std::string> names;
  for (const auto& e : in.effects) names.push_back(e.name);
  d.h(2, "before-after",
      names.empty() ? std::string("Before and after adding the effects")
                    : fmt::format("Before and after adding {}", fmt::join(names, " and ")));
  const std::string change = residual_change_chart(c, *in.baseline, *in.with_effects, "resid-change");
  if (!change.empty())
    d.figure(change, "Each compared value's E/u_val as the models are (hollow) and with the effects (filled), "
                     "joined by a line.");
  d.table(change_in_words(*in.dataset, *in.baseline, *in.with_effects));
  d.table(effects_table(in.effects));
  for (const auto& e : in.effects) {
    if (std::find(described.begin(), described.end(), e.name) != described.end()) continue;
    std::string body = e.physics.empty() ? "No description of its physics was supplied." : e.physics;
    if (!e.source.empty()) body += " Source: " + e.source + ".";
    d.definition(fmt::format("{} ({})", e.name, e.parameter), body);
  }
  d.table(rms_change_table(c, *in.baseline, *in.with_effects));
  const std::string chart = rms_bar_chart(c, *in.baseline, *in.with_effects, "rms-before-after");
  if (!chart.empty())
    d.figure(chart, "RMS E/u_val per model (all compared values), before and after; the dashed line is what the "
                    "stated uncertainties alone give.");
}

// A section drawn once per variant. Without effects, just the models as they are; with effects a
// pair, one titled column each, which report.html lays side by side and report.md merges. `fill`
// gets the other variant's result when it draws a column (charts then share scales and are drawn
// kPairChartWidth wide), else nullptr.
template <class Fill>
void per_variant(Doc& d, const std::vector<Variant>& vs, const std::string& section, Fill fill) {
  if (vs.size() == 1) {
    fill(d, vs[0], static_cast<const ValidationResult*>(nullptr));
    return;
  }
  Doc before, after;
  before.h(3, section + "-" + vs[0].suffix, vs[0].title);
  fill(before, vs[0], vs[1].result);
  after.h(3, section + "-" + vs[1].suffix, vs[1].title);
  fill(after, vs[1], vs[0].result);
  d.pair(section + "-pair", std::move(before), std::move(after), vs[1].title);
}

// A sentence of the diagnosis that speaks statistics (chi-square, BIC, a p-value, the test and its
// correction): it belongs under "How sure is this?", not among the findings in the quantities' words.
bool statistical(const std::string& sentence) {
  for (const char* w : {"chi^2", "χ²", "BIC", " p = ", "p (adjusted", "Bonferroni", "likelihood-ratio"})
    if (sentence.find(w) != std::string::npos) return true;
  return false;
}

std::vector<std::string> in_words(const std::vector<std::string>& sentences, bool statistics) {
  std::vector<std::string> out;
  for (const auto& s : sentences)
    if (statistical(s) == statistics) out.push_back(s);
  return out;
}

// The diagnosis's evidence: which candidate explains the misfit, how well, and what else could.
// Its verdict heads the report and its "where the models fail" sentences sit under the residual
// chart; this section holds the rest of DiagnosisResult.
void what_is_missing(Doc& d, const Context& c) {
  const auto& g = *c.in.diagnosis;
  d.h(2, "missing", "What is missing: the candidate effects");
  d.p(fmt::format("Models: {}; {} measured values with uncertainties ({} without, which the diagnosis cannot weigh "
                  "and leaves out).",
                  fmt::join(g.models, ", "), g.n_data, g.n_without_uncertainty));
  if (const auto findings = in_words(g.findings, false); !findings.empty()) {
    d.h(3, "missing-data", "What the data say about themselves");
    d.list(findings);
  }
  d.h(3, "missing-ranking", "Which effect explains the misfit");
  const std::string chart = ranking_chart(g, "ranking-chart");
  if (!chart.empty())
    d.figure(chart, "Share of the misfit beyond noise that each candidate effect explains when fitted; those "
                    "beyond chance in colour, the recommended one highlighted.");
  d.table(ranking_table(g));
  if (std::any_of(g.singles.begin(), g.singles.end(), [](const auto& f) { return f.is_record(); })) {
    d.h(3, "missing-record", "Is the rig's record wrong?");
    d.p("Each recorded input that a rig's record can get wrong (plate position and angle, pulley and belt, belt "
        "speed, mass flow, particle size, bulk density, a measured stream thickness) was tried as a candidate "
        "beside the physical effects: its error, truth minus record, fitted to the same data and tested against "
        "the same family-wise false-alarm rate.");
    d.table(ranking_table(g, true));
  }

  if (const auto* best = g.best()) {
    d.h(3, "missing-physics",
        g.convincing ? (best->is_record() ? "The recorded input to check: " : "The recommended effect: ") + best->label()
                     : fmt::format("The best explanation, which leaves a misfit that is not noise: {}",
                                   best->label()));
    // The command that fits the candidate (both effects of a pair) to the dataset, as the shell takes it.
    std::string fit_flags;
    for (const auto& nm : best->effects)
      fit_flags += (fit_flags.empty() ? "" : " ") + std::string(best->is_record() ? "--input " : "--effect ") +
                   shell_word(nm + "=fit");
    for (std::size_t i = 0; i < best->effects.size(); ++i) {
      const auto& nm = best->effects[i];
      std::string fit;
      if (i < best->estimate.size() && i < best->parameters.size())
        fit = fmt::format("Diagnosis estimate: {} = {:.4g}{}.", best->parameters[i], best->estimate[i],
                          i < best->uncertainty.size() && std::isfinite(best->uncertainty[i])
                              ? fmt::format(" ± {:.2g}", best->uncertainty[i])
                              : std::string(" (unconstrained)"));
      const auto e = std::find_if(c.in.effects.begin(), c.in.effects.end(),
                                  [&](const EffectDescription& x) { return x.name == nm; });
      if (e == c.in.effects.end()) {
        std::string body = fit;
        if (const auto p = c.in.candidate_physics.find(nm); p != c.in.candidate_physics.end() && !p->second.empty())
          body += " " + p->second;
        d.definition(nm, body + " To see the models with it: " + validate_command(c.in, fit_flags, fmt::format("{}", fmt::join(best->effects, "-"))) + ".");
        continue;
      }
      std::string body = fit;
      body += fmt::format(" Applied in this report: {} = {:.4g}{}{}.", e->parameter, e->value,
                          e->uncertainty ? fmt::format(" ± {:.2g}", *e->uncertainty) : std::string(),
                          e->unit.empty() ? std::string() : " " + e->unit);
      if (!e->physics.empty()) body += " " + e->physics;
      if (!e->source.empty()) body += " Source: " + e->source + ".";
      d.definition(nm, body);
    }
  } else if (g.verdict_code == validation::Verdict::out_of_range) {
    d.p("No candidate effect is named: the data want an effect at a strength outside its physical range (the "
        "verdict above), and no effect inside its range explains them as well.");
  } else {
    d.p("No candidate effect is significant: none of the library's effects explains the misfit better than "
        "chance would.");
  }
  if (!g.indistinguishable.empty() || !g.discriminators.empty()) {
    d.h(3, "missing-alternatives", "Alternatives the data cannot tell apart");
    if (!g.indistinguishable.empty())
      d.p(fmt::format("About as good as the best: {}.", fmt::join(g.indistinguishable, ", ")));
    d.list(g.discriminators);
  }
  if (const auto caveats = in_words(g.caveats, false); !caveats.empty()) {
    d.h(3, "missing-caveats", "Caveats");
    d.list(caveats);
  }
}

// The statistics behind the diagnosis, closed until opened: the verdict and the ranking above speak
// in the quantities' units and %; this is for whoever asks how sure they are.
void how_sure(Doc& d, const validation::DiagnosisResult& g) {
  d.folded_h2("how-sure", "How sure is this?");
  if (!g.evidence.empty()) d.p(g.evidence);
  d.p(fmt::format("With the uncertainties as stated, χ² of the models as they are is {:.1f} for {} data (chance of "
                  "this much from noise alone: p = {:.2g}); the figures above and in the table are under the "
                  "diagnosis's noise model (the uncertainties widened, and model discrepancies added, where the "
                  "data ask for it).",
                  g.chi2_baseline, g.n_data, g.baseline_p_value));
  d.table(statistics_table(g));
  // The method and the data's scatter as the statistics see them.
  std::vector<std::string> method = in_words(g.findings, true);
  for (auto& c : in_words(g.caveats, true)) method.push_back(std::move(c));
  d.list(method);
}

// Every value outside its tolerance, with the limit in the quantity's unit.
Table failure_table(const validation::ValidationResult& r) {
  Table t;
  t.id = "failures-table";
  t.caption = "Values outside tolerance";
  t.key_columns = 3;
  t.columns = {{"", "condition", "", true}, {"", "model", "", true},     {"", "quantity", "", true},
               {"", "measured", "", false}, {"", "predicted", "", false}, {"", "error", "", false},
               {"", "allowed error (limit)", "", true}};
  for (const auto& f : validation::failed_values(r))
    t.rows.push_back({{f.condition, "", false, "", true},
                      {f.model, "", false, "", true},
                      {f.quantity, "", false, "", true},
                      {f.measured},
                      {f.predicted},
                      {f.error},
                      {f.limit, "", false, "", true}});
  t.notes.push_back("Error = predicted − measured, in the quantity's unit and in per cent of the measured value; the "
                    "limit is the largest error the tolerance allows for that value.");
  return t;
}

// The title and what was compared: the dataset, the models and effects, the acceptance's verdict
// (and the other result's count beside it, which decides nothing: api/validate.h), and how many
// conditions the per-condition tables show. No date: the report is a function of its inputs.
void title_and_facts(Doc& d, const Context& c) {
  const ReportInput& in = c.in;
  const std::string folder =
      in.baseline->dataset_folder.empty() ? in.baseline->dataset_name : in.baseline->dataset_folder;
  d.h(1, "top", "chutelab validation report: " + folder);
  std::vector<std::string> meta;
  meta.push_back(fmt::format("Dataset: {}{}; {} conditions, {} measured values, {} trajectory points", folder,
                             folder == in.baseline->dataset_name ? std::string()
                                                                 : " (rig " + in.baseline->dataset_name + ")",
                             c.conditions.size() + c.conditions_left_out, in.dataset->measurements.size(),
                             in.dataset->trajectory.size()));
  meta.push_back(fmt::format("Models: {}; effects: {}", fmt::join(in.baseline->models, ", "),
                             in.with_effects ? effects_label(*in.with_effects) : std::string("none")));
  const ValidationResult& judged = in.accepted();
  const bool effects_judged = in.accepted_with_effects && in.with_effects;
  if (judged.acceptance_checked) {
    const std::string who = !in.with_effects ? std::string()
                            : effects_judged ? " of the models with " + effects_label(*in.with_effects)
                                             : std::string(" of the models as delivered");
    meta.push_back(judged.acceptance_failed
                       ? fmt::format("Acceptance{}: FAILED, {} of {} checked values outside tolerance (marked ✗; "
                                     "listed under \"Outside tolerance\")",
                                     who, judged.failed_count(), judged.checked_count())
                       : fmt::format("Acceptance{}: passed, {} values checked", who, judged.checked_count()));
    if (const ValidationResult* other = in.beside_acceptance())
      meta.push_back(fmt::format("{}: {} of {} checked values outside tolerance (beside the acceptance; not judged)",
                                 effects_judged ? std::string("Models as delivered")
                                                : "With " + effects_label(*other),
                                 other->failed_count(), other->checked_count()));
  } else {
    meta.push_back("Acceptance: no tolerances set");
  }
  if (c.conditions_left_out > 0)
    meta.push_back(fmt::format("Shown: the {} conditions of largest misfit (largest |E/u_val|) in every "
                               "per-condition table and chart; {} more are in predictions.csv and errors.csv and in "
                               "every summary statistic",
                               c.conditions.size(), c.conditions_left_out));
  d.list(meta);
}

// The verdict in words (the diagnosis's, then the plain-words summary; or the summary alone), and
// the warning when the effects added are not what the diagnosis points to.
void verdict_in_words(Doc& d, const ReportInput& in) {
  std::string words;
  for (const auto& sentence : in_short(in)) words += (words.empty() ? "" : " ") + sentence;
  if (in.diagnosis) {
    d.verdict(in.diagnosis->verdict);
    d.p(words);
  } else {
    d.verdict(words);
  }
  d.warning(effect_choice_warning(in));
}

// The models as they are, every E/u_val, and in words the quantities beyond the noise.
void where_the_models_fail(Doc& d, const Context& c) {
  const ReportInput& in = c.in;
  d.h(2, "residuals", "Where the models fail");
  const std::string chart = residual_chart(c, *in.baseline, "resid-base", 980.0);
  if (chart.empty()) d.p("No compared value has a stated uncertainty: no normalised error to show.");
  else
    d.figure(chart, "E/u_val per condition and quantity for the models as they are, conditions ordered by belt "
                    "speed, then mass flow: inside the shaded band (|E/u_val| ≤ 2) the difference is what the "
                    "stated uncertainties explain; outside it the model misses something.");
  if (in.diagnosis) {
    if (in.diagnosis->failure_summary.empty())
      d.p("Every quantity is within about two uncertainties of its measurement.");
    d.list(in.diagnosis->failure_summary);
  } else {
    std::vector<std::string> lines;
    for (auto l : misfit_lines(in, 12)) lines.push_back(l.erase(0, l.find_first_not_of(' ')));
    d.list(lines);
  }
}

// Values outside tolerance (the CI's question): those judged, then those beside.
void outside_tolerance(Doc& d, const ReportInput& in) {
  const ValidationResult& judged = in.accepted();
  const ValidationResult* other = in.beside_acceptance();
  const bool judged_out = judged.acceptance_checked && (judged.acceptance_failed || !judged.acceptance_problems.empty());
  const bool other_out = other && other->acceptance_checked && other->failed_count() > 0;
  if (!judged_out && !other_out) return;
  d.h(2, "failures", "Outside tolerance");
  const std::string judged_title = !other                    ? std::string()
                                   : in.accepted_with_effects ? "The models with " + effects_label(judged)
                                                              : std::string("The models as delivered");
  if (judged_out) {
    if (other) d.p(judged_title + " (judged by the acceptance):");
    const Table failed = failure_table(judged);
    if (failed.rows.empty()) d.p("No value is outside its limits; acceptance failed for the reasons below.");
    d.table(failed);
    std::vector<std::string> problems;
    for (const auto& p : judged.acceptance_problems) problems.push_back("Acceptance problem: " + p);
    d.list(problems);
  } else {
    d.p(judged_title + " (judged by the acceptance): every checked value is within its limits.");
  }
  if (other_out) {
    d.p(fmt::format("{} (beside the acceptance, not judged):",
                    in.accepted_with_effects ? std::string("The models as delivered")
                                             : "With " + effects_label(*other)));
    Table t = failure_table(*other);
    t.id = "failures-table-beside";
    t.caption = "Values outside tolerance beside the acceptance";
    d.table(t);
  }
}

void summary_section(Doc& d, const std::vector<Variant>& vs) {
  d.h(2, "summary", "Summary per model and quantity");
  std::vector<std::string> lines;
  for (const auto& v : vs)
    for (const auto& m : v.result->models)
      if (auto z = v.result->overall_rms_normalised(m))
        lines.push_back(fmt::format("{} — {}: RMS E/u_val {:.2f} over all compared values{}", v.title, m, *z,
                                    *z > 2.0 ? " (more than the stated uncertainties explain)" : ""));
  d.list(lines);
  per_variant(d, vs, "summary", [&](Doc& x, const Variant& v, const ValidationResult*) {
    x.table(summary_table(*v.result, "summary-table-" + v.suffix));
  });
}

// The rig's logs behind the plate's measurements.
void logs_section(Doc& d, const ReportInput& in) {
  if (in.log_charts.empty()) return;
  d.h(2, "logs", "The rig's logs");
  d.p("The plate's measurements were read from the rig's logs: the steady window found in each (not chosen), the "
      "zero from its unloaded parts before and after, its drift and any creep, and an uncertainty that counts the "
      "samples' correlation (log_provenance.csv of import-logs lists every number).");
  d.figure(log_charts_html(in.log_charts, "logchart"),
           "The plate's load as logged per condition, with its steady window, zero and trend");
  d.list(in.log_lines);
}

// The reference study's Table 4 and Fig. 6.
void forces_section(Doc& d, const Context& c, const std::vector<Variant>& vs) {
  d.h(2, "forces", "Plate forces");
  per_variant(d, vs, "forces", [&](Doc& x, const Variant& v, const ValidationResult* other) {
    x.table(force_table(c, *v.result, "table4-" + v.suffix));
    const std::string chart =
        force_bar_chart(c, *v.result, "bars-" + v.suffix, other ? kPairChartWidth : 960.0, other);
    if (!chart.empty())
      x.figure(chart, "Resultant plate force R per condition (cf. the reference study's Fig. 6); error bars: ±1 sd "
                      "of the measurement.");
    else x.p("Neither measured nor predicted: the resultant force R.");
  });
}

// The reference study's Table 5.
void velocities_section(Doc& d, const Context& c, const std::vector<Variant>& vs) {
  d.h(2, "velocities", "Stream velocities and impact point");
  per_variant(d, vs, "velocities", [&](Doc& x, const Variant& v, const ValidationResult*) {
    x.table(velocity_table(c, *v.result, "table5-" + v.suffix));
  });
}

// The reference study's Fig. 7.
void trajectories_section(Doc& d, const Context& c, const std::vector<Variant>& vs) {
  d.h(2, "trajectories", "Stream trajectories");
  d.p("Each panel: the head pulley at the origin, the plate face, each model's streamlines, the measured stream "
      "points (± 1 sd) and the measured and predicted impact points on the plate face. Equal scales on both "
      "axes; the view ends a little below the lowest impact point. Beside each panel, the plate face "
      "magnified (\u201cat the plate\u201d): where each streamline arrives, the models' impact points and the "
      "measured one with its ± 1 sd.");
  per_variant(d, vs, "trajectories", [&](Doc& x, const Variant& v, const ValidationResult* other) {
    x.figure(trajectory_grid(c, *v.result, "traj-" + v.suffix, other ? kPairChartWidth : 980.0),
             "Stream trajectories per condition (cf. the reference study's Fig. 7)");
  });
}

// Residual trends (and, with effects, both residual charts on one scale).
void trends_section(Doc& d, const Context& c, const std::vector<Variant>& vs) {
  d.h(2, "trends", c.in.with_effects ? "Residuals before and after, and their trends" : "Residual trends");
  per_variant(d, vs, "trends", [&](Doc& x, const Variant& v, const ValidationResult* other) {
    if (other) {
      const std::string chart = residual_chart(c, *v.result, "resid-" + v.suffix + "-pair", kPairChartWidth, other);
      if (!chart.empty())
        x.figure(chart, "E/u_val per condition and quantity (E = predicted − measured, u_val = V&V 20 validation "
                        "uncertainty); both columns on one scale.");
    }
    x.table(trend_table(c, *v.result, "trends-" + v.suffix));
  });
}

// Plate loading and wear, only when a model gave a map.
void plate_loading_section(Doc& d, const Context& c) {
  const PlateSection ps = plate_section(c, *c.in.baseline, "platemap", 980.0);
  if (ps.empty()) return;
  d.h(2, "plate", "Plate loading and wear");
  d.p("The mean normal pressure and the wear rate on the plate face over each run's steady window, per cell of "
      "the map (by default 10 mm cells on which the plate's contacts are binned; setup.toml [dem] map_cell_mm "
      "sets the size, 0 gives the coarse plate's own two triangles; a run read from a cache entry recorded "
      "before the grid shows those two triangles), seen from the pulley: z across, y up, in mm. One "
      "colour scale per quantity for every condition. The dashed box is the analytical impact zone (Booth/CEMA "
      "upper and lower limits, loaded width; Korzen's R_n spread over it as a mean pressure), the dotted line "
      "its centroid streamline.");
  d.figure(ps.pressure_svg, "Normal pressure on the plate face per condition");
  d.figure(ps.wear_svg, "Wear rate (Archard sliding + Finnie impact) on the plate face per condition");
  d.table(ps.table);
}

void findings_section(Doc& d, const ReportInput& in) {
  if (!in.findings || !any_testable(*in.findings)) return;
  d.h(2, "findings", "The reference study's findings");
  d.table(findings_table(*in.findings));
}

// Provenance of the numbers: the dataset's source, the run's notes, each model's notes.
void provenance_section(Doc& d, const Context& c) {
  const ReportInput& in = c.in;
  const ValidationResult& last = in.with_effects ? *in.with_effects : *in.baseline;
  const Table notes = model_notes_table(c, last, "model-notes");
  if (notes.rows.empty() && in.notes.empty() && in.dataset->setup.source.empty()) return;
  d.h(2, "provenance", "How the numbers were obtained");
  std::vector<std::string> lines;
  if (!in.dataset->setup.source.empty()) lines.push_back("Dataset source: " + in.dataset->setup.source);
  for (const auto& n : in.notes) lines.push_back(n);
  d.list(lines);
  d.table(notes);
}

// Studies run beside the validation (reports/studies.h).
void studies_sections(Doc& d, const ReportInput& in) {
  for (const auto& s : in.studies ? *in.studies : std::vector<StudySection>{}) {
    d.h(2, s.id, s.title);
    if (!s.verdict.empty()) d.verdict(s.verdict);
    for (const auto& p : s.paragraphs) d.p(p);
    d.table(s.table);
    if (!s.chart_svg.empty()) d.figure(s.chart_svg, s.caption);
  }
}

// Appendix: V&V 20, the parts of the validation uncertainty.
void vv20_appendix(Doc& d, const Context& c) {
  const ReportInput& in = c.in;
  d.folded_h2("vv20", "Appendix: validation uncertainty (V&V 20)");
  d.p("E = S − D (prediction minus data); u_val = sqrt(u_D² + u_num² + u_input²), the measurement's, the model's "
      "numerical and the inputs' standard uncertainties combined; |E|/u_val ≤ 2 is agreement within them.");
  d.list(vv20_not_estimated(*in.dataset, *in.baseline));
  if (!in.with_effects) {
    d.table(vv20_table(c, *in.baseline, "vv20-table"));
  } else {
    d.h(3, "vv20-base", "The models as they are");
    d.table(vv20_table(c, *in.baseline, "vv20-table"));
    d.h(3, "vv20-effects", "With effects: " + effects_label(*in.with_effects));
    d.table(vv20_table(c, *in.with_effects, "vv20-table-effects"));
  }
}

}  // namespace

Doc assemble(const ReportInput& in) {
  if (!in.dataset || !in.baseline) throw std::invalid_argument("report: dataset and baseline are required");
  const Context c = make_context(in);
  const auto vs = variants(in);
  Doc d;
  // The story first: what was compared, the verdict in words, where the models fail and what
  // falls outside tolerance; what an added effect changes, then the diagnosis's evidence.
  title_and_facts(d, c);
  verdict_in_words(d, in);
  where_the_models_fail(d, c);
  outside_tolerance(d, in);
  before_after(d, c, in.diagnosis && in.diagnosis->best() ? in.diagnosis->best()->effects : std::vector<std::string>{});
  if (in.diagnosis) what_is_missing(d, c);
  if (in.diagnosis) how_sure(d, *in.diagnosis);
  // The detail.
  summary_section(d, vs);
  logs_section(d, in);
  forces_section(d, c, vs);
  velocities_section(d, c, vs);
  trajectories_section(d, c, vs);
  trends_section(d, c, vs);
  plate_loading_section(d, c);
  findings_section(d, in);
  provenance_section(d, c);
  studies_sections(d, in);
  vv20_appendix(d, c);
  return d;
}

}  // namespace chutelab::reports
