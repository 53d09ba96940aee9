// The report: one assembly of sections, rendered twice (Markdown for diffs and terminals, HTML with
// inline SVG for reading and printing). Sections and tables come from the same builders, so the
// two files never disagree. No clock, no random ids, no locale: same inputs, same bytes.
#include "reports/report.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <cctype>
#include <map>
#include <stdexcept>

#include "reports/common.h"
#include "reports/plain_summary.h"
#include "reports/studies.h"
#include "validation/failed_values.h"
#include "validation/quantity_misfit.h"

namespace chutelab::reports {
namespace {

using validation::ValidationResult;

// Both renderers walk the same list of blocks.
struct Block {
  enum class Kind { heading, paragraph, list, table, figure, verdict, warning, definition, pair } kind{};
  int level = 2;                    // headings
  std::string id{};                 // headings: anchor
  std::string text{};               // plain text (headings, paragraphs, verdict, definition term)
  std::string detail{};             // definition body (plain)
  std::vector<std::string> items{}; // lists (plain)
  Table table{};
  std::string svg_html{};           // figures: ready HTML (inline SVG)
  std::string caption{};            // figures: plain
  std::string after_svg_html{};     // a figure of report.md's merged pair: the "after" column's chart
  // pair: the same blocks for the models as they are and with effects, which report.html shows
  // side by side; `merged` is what report.md shows instead (empty: the two one after the other).
  std::vector<Block> before{}, after{}, merged{};
  bool folded = false;              // level-2 headings: report.html shows the section closed
};

// report.md cannot put two tables side by side: a pair becomes one table per table with before and
// after columns, one line per figure and the rest once where both say the same. Empty when the
// two columns do not line up (then both are shown, one after the other).
std::vector<Block> merge_for_markdown(const std::vector<Block>& before, const std::vector<Block>& after,
                                      const std::string& after_title) {
  if (before.size() != after.size()) return {};
  std::vector<Block> out;
  for (std::size_t k = 0; k < before.size(); ++k) {
    const Block &b = before[k], &a = after[k];
    if (b.kind != a.kind) return {};
    switch (b.kind) {
      case Block::Kind::heading: break;  // the columns' titles: the merged columns say before/after
      case Block::Kind::table: {
        std::string after_what = after_title;
        if (!after_what.empty() && after_what[0] >= 'A' && after_what[0] <= 'Z') after_what[0] += 'a' - 'A';
        auto t = merge_before_after(b.table, a.table, "before", "after",
                                    "\"before\": the models as they are; \"after\": " + after_what);
        if (!t) return {};
        out.push_back(b);
        out.back().table = std::move(*t);
        break;
      }
      case Block::Kind::figure: {
        std::string what = b.caption.empty() ? std::string("Chart") : b.caption;
        if (what.ends_with('.')) what.pop_back();
        out.push_back(b);
        out.back().caption = what + " — before and after";
        out.back().after_svg_html = a.svg_html;
        break;
      }
      default:
        if (b.text != a.text || b.items != a.items || b.detail != a.detail) return {};
        out.push_back(b);
    }
  }
  return out;
}

class Doc {
 public:
  void h(int level, std::string id, std::string text) {
    blocks.push_back({Block::Kind::heading, level, std::move(id), std::move(text)});
  }
  void p(std::string text) {
    if (!text.empty()) blocks.push_back({Block::Kind::paragraph, 0, {}, std::move(text)});
  }
  void list(std::vector<std::string> items) {
    if (items.empty()) return;
    Block b{Block::Kind::list};
    b.items = std::move(items);
    blocks.push_back(std::move(b));
  }
  void table(Table t) {
    if (t.rows.empty()) return;
    Block b{Block::Kind::table};
    b.table = std::move(t);
    blocks.push_back(std::move(b));
  }
  void figure(std::string html, std::string caption) {
    Block b{Block::Kind::figure};
    b.svg_html = std::move(html);
    b.caption = std::move(caption);
    blocks.push_back(std::move(b));
  }
  void verdict(std::string text) { blocks.push_back({Block::Kind::verdict, 0, {}, std::move(text)}); }
  void warning(std::string text) {
    if (!text.empty()) blocks.push_back({Block::Kind::warning, 0, {}, std::move(text)});
  }
  // A section whose detail the reader opens when wanted (report.html: a closed <details>).
  void folded_h2(std::string id, std::string text) {
    h(2, std::move(id), std::move(text));
    blocks.back().folded = true;
  }
  // `id`: the HTML element holding both columns.
  void pair(std::string id, Doc before, Doc after, const std::string& after_title) {
    Block b{Block::Kind::pair};
    b.id = std::move(id);
    b.merged = merge_for_markdown(before.blocks, after.blocks, after_title);
    b.before = std::move(before.blocks);
    b.after = std::move(after.blocks);
    blocks.push_back(std::move(b));
  }
  void definition(std::string term, std::string body) {
    Block b{Block::Kind::definition};
    b.text = std::move(term);
    b.detail = std::move(body);
    blocks.push_back(std::move(b));
  }
  std::vector<Block> blocks;
};

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

Doc assemble(const ReportInput& in) {
  if (!in.dataset || !in.baseline) throw std::invalid_argument("report: dataset and baseline are required");
  const Context c = make_context(in);
  const auto vs = variants(in);
  const ValidationResult& last = in.with_effects ? *in.with_effects : *in.baseline;
  Doc d;

  // ---- The story first: what was compared, the verdict in words, and the warning if any ----
  // (No date: the report is a function of its inputs.)
  const std::string folder =
      in.baseline->dataset_folder.empty() ? in.baseline->dataset_name : in.baseline->dataset_folder;
  d.h(1, "top", "chutelab validation report: " + folder);
  {
    std::vector<std::string> meta;
    meta.push_back(fmt::format("Dataset: {}{}; {} conditions, {} measured values, {} trajectory points", folder,
                               folder == in.baseline->dataset_name ? std::string()
                                                                   : " (rig " + in.baseline->dataset_name + ")",
                               c.conditions.size() + c.conditions_left_out, in.dataset->measurements.size(),
                               in.dataset->trajectory.size()));
    meta.push_back(fmt::format("Models: {}; effects: {}", fmt::join(in.baseline->models, ", "),
                               in.with_effects ? effects_label(*in.with_effects) : std::string("none")));
    // Both verdicts: the one the acceptance (validate's exit code, the JUnit file) gives, and the
    // other result's count beside it, which decides nothing (api/validate.h).
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
  std::string words;
  for (const auto& sentence : in_short(in)) words += (words.empty() ? "" : " ") + sentence;
  if (in.diagnosis) {
    d.verdict(in.diagnosis->verdict);
    d.p(words);
  } else {
    d.verdict(words);
  }
  d.warning(effect_choice_warning(in));

  // ---- Where the models fail: the models as they are, every E/u_val ----
  d.h(2, "residuals", "Where the models fail");
  {
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

  // ---- Values outside tolerance (the CI's question): those judged, then those beside ----
  {
    const ValidationResult& judged = in.accepted();
    const ValidationResult* other = in.beside_acceptance();
    const bool judged_out = judged.acceptance_checked && (judged.acceptance_failed || !judged.acceptance_problems.empty());
    const bool other_out = other && other->acceptance_checked && other->failed_count() > 0;
    if (judged_out || other_out) {
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
  }

  // ---- What an added effect changes, then the diagnosis's evidence ----
  before_after(d, c, in.diagnosis && in.diagnosis->best() ? in.diagnosis->best()->effects : std::vector<std::string>{});
  if (in.diagnosis) what_is_missing(d, c);
  if (in.diagnosis) how_sure(d, *in.diagnosis);

  // ---- The detail ----
  d.h(2, "summary", "Summary per model and quantity");
  {
    std::vector<std::string> lines;
    for (const auto& v : vs)
      for (const auto& m : v.result->models)
        if (auto z = v.result->overall_rms_normalised(m))
          lines.push_back(fmt::format("{} — {}: RMS E/u_val {:.2f} over all compared values{}", v.title, m, *z,
                                      *z > 2.0 ? " (more than the stated uncertainties explain)" : ""));
    d.list(lines);
  }
  per_variant(d, vs, "summary", [&](Doc& x, const Variant& v, const ValidationResult*) {
    x.table(summary_table(*v.result, "summary-table-" + v.suffix));
  });

  // ---- The rig's logs behind the plate's measurements ----
  if (!in.log_charts.empty()) {
    d.h(2, "logs", "The rig's logs");
    d.p("The plate's measurements were read from the rig's logs: the steady window found in each (not chosen), the "
        "zero from its unloaded parts before and after, its drift and any creep, and an uncertainty that counts the "
        "samples' correlation (log_provenance.csv of import-logs lists every number).");
    d.figure(log_charts_html(in.log_charts, "logchart"),
             "The plate's load as logged per condition, with its steady window, zero and trend");
    d.list(in.log_lines);
  }

  // ---- Reference study Table 4 and Fig. 6 ----
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

  // ---- Reference study Table 5 ----
  d.h(2, "velocities", "Stream velocities and impact point");
  per_variant(d, vs, "velocities", [&](Doc& x, const Variant& v, const ValidationResult*) {
    x.table(velocity_table(c, *v.result, "table5-" + v.suffix));
  });

  // ---- Reference study Fig. 7 ----
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

  // ---- Residual trends (and, with effects, both residual charts on one scale) ----
  d.h(2, "trends", in.with_effects ? "Residuals before and after, and their trends" : "Residual trends");
  per_variant(d, vs, "trends", [&](Doc& x, const Variant& v, const ValidationResult* other) {
    if (other) {
      const std::string chart = residual_chart(c, *v.result, "resid-" + v.suffix + "-pair", kPairChartWidth, other);
      if (!chart.empty())
        x.figure(chart, "E/u_val per condition and quantity (E = predicted − measured, u_val = V&V 20 validation "
                        "uncertainty); both columns on one scale.");
    }
    x.table(trend_table(c, *v.result, "trends-" + v.suffix));
  });

  // ---- Plate loading and wear (only when a model gave a map) ----
  {
    const PlateSection ps = plate_section(c, *in.baseline, "platemap", 980.0);
    if (!ps.empty()) {
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
  }

  if (in.findings && any_testable(*in.findings)) {
    d.h(2, "findings", "The reference study's findings");
    d.table(findings_table(*in.findings));
  }

  // ---- Provenance of the numbers ----
  const Table notes = model_notes_table(c, last, "model-notes");
  if (!notes.rows.empty() || !in.notes.empty() || !in.dataset->setup.source.empty()) {
    d.h(2, "provenance", "How the numbers were obtained");
    std::vector<std::string> lines;
    if (!in.dataset->setup.source.empty()) lines.push_back("Dataset source: " + in.dataset->setup.source);
    for (const auto& n : in.notes) lines.push_back(n);
    d.list(lines);
    d.table(notes);
  }
  // ---- Studies run beside the validation (reports/studies.h) ----
  for (const auto& s : in.studies ? *in.studies : std::vector<StudySection>{}) {
    d.h(2, s.id, s.title);
    if (!s.verdict.empty()) d.verdict(s.verdict);
    for (const auto& p : s.paragraphs) d.p(p);
    d.table(s.table);
    if (!s.chart_svg.empty()) d.figure(s.chart_svg, s.caption);
  }

  // ---- Appendix: V&V 20, the parts of the validation uncertainty ----
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
  return d;
}

constexpr std::string_view kCss = R"(
:root { --ink:#1b1b1b; --muted:#5a5a5a; --rule:#d0d0d0; --fail:#fbd5d5; --failink:#8e1b1b; }
* { box-sizing: border-box; }
body { margin: 0; color: var(--ink); background: #fff;
  font: 14px/1.45 system-ui, -apple-system, "Segoe UI", Roboto, "Helvetica Neue", Arial, sans-serif; }
main { max-width: 1100px; margin: 0 auto; padding: 24px 20px 60px; }
h1 { font-size: 24px; margin: 0 0 10px; }
h2 { font-size: 19px; margin: 34px 0 10px; padding-bottom: 4px; border-bottom: 2px solid var(--ink); }
h3 { font-size: 15px; margin: 22px 0 8px; }
ul { padding-left: 22px; }
nav.toc { font-size: 13px; margin: 10px 0 0; }
nav.toc a { margin-right: 14px; color: #0b5394; text-decoration: none; }
.meta { list-style: none; padding: 0; margin: 0 0 8px; color: var(--muted); }
.verdict { font-weight: 600; font-size: 15px; border-left: 4px solid #D55E00; padding: 8px 12px; background: #fff4ec; }
.warning { border-left: 4px solid #b00020; padding: 6px 12px; background: #fdecee; }
details.fold > summary { cursor: pointer; list-style-position: outside; }
details.fold > summary h2 { display: inline-block; width: calc(100% - 24px); }
dl.effect { margin: 8px 0; } dl.effect dt { font-weight: 600; } dl.effect dd { margin: 2px 0 8px 18px; }
.table-wrap { overflow-x: auto; margin: 8px 0; }
table.data { border-collapse: collapse; font-size: 12.5px; font-variant-numeric: tabular-nums; }
table.data caption { text-align: left; font-weight: 600; padding: 2px 0 6px; }
table.data th, table.data td { padding: 3px 5px; border-bottom: 1px solid var(--rule); white-space: nowrap; }
table.data th { background: #f1f1f1; font-weight: 600; text-align: right; vertical-align: bottom; white-space: normal; }
table.data tr.group th { text-align: center; border-bottom: 1px solid #999; background: #e7e7e7; }
table.data td.num { text-align: right; }
table.data td.left, table.data th.left { text-align: left; white-space: normal; }
table.data td.fail { background: var(--fail); color: var(--failink); }
table.data td.beyond { background: #fff1c9; }
table.data td .mark { font-weight: 700; }
table.data td .u { color: var(--muted); font-size: 11px; }
.table-note { font-size: 12px; color: var(--muted); margin: 2px 0 8px; }
figure { margin: 12px 0 18px; }
figcaption { font-size: 12px; color: var(--muted); margin-top: 4px; }
svg.plot { display: block; max-width: 100%; height: auto; font-family: inherit; background: #fff; }
svg.plot text { font-family: inherit; fill: #1b1b1b; }
.traj-grid { display: flex; flex-wrap: wrap; gap: 10px 14px; align-items: flex-start; }
.traj-grid svg.plot { flex: 0 1 auto; }
/* Before and after adding effects side by side, the pair wider than the text (centred on it) so
   that each column holds a chart drawn for it at full size; one under the other where two columns
   would not fit. */
.before-after { display: grid; grid-template-columns: minmax(0, 1fr) minmax(0, 1fr); gap: 0 28px;
  align-items: start; width: min(1800px, calc(100vw - 48px));
  margin-left: calc((100% - min(1800px, calc(100vw - 48px))) / 2); }
.ba-col { min-width: 0; }
.ba-col > h3:first-child { margin-top: 10px; padding-bottom: 3px; border-bottom: 1px solid var(--rule); }
/* Half the width for the same tables: tighter cells, a measurement's sd under its value. */
.before-after table.data { font-size: 11.5px; }
.before-after table.data th, .before-after table.data td { padding: 3px 4px; }
.before-after table.data td .u { display: block; line-height: 1.1; }
.before-after table.data td.left:first-child { white-space: nowrap; }
/* A table wider than its column scrolls; the row's name stays in view. */
.before-after table.data td:first-child { position: sticky; left: 0; background: #fff; }
.before-after table.data th:first-child { position: sticky; left: 0; }
@media (max-width: 1199px) { .before-after { display: block; width: auto; margin-left: 0; } }
@media (max-width: 1799px) { .before-after.wide { display: block; } }
/* A narrow window still shows Table 5 whole: smaller cells rather than a scroll bar. */
@media (max-width: 999px) {
  table.data, .before-after table.data { font-size: 11px; }
  table.data th, table.data td, .before-after table.data th, .before-after table.data td { padding: 2px 3px; }
}
footer { margin-top: 40px; font-size: 12px; color: var(--muted); }
@media print {
  .before-after { display: block; width: auto; margin-left: 0; }
  body { font-size: 11px; } main { max-width: none; padding: 0; }
  nav.toc { display: none; }
  h2 { break-after: avoid; } figure, .table-wrap, svg.plot { break-inside: avoid; }
  table.data td.fail, table.data td.beyond { -webkit-print-color-adjust: exact; print-color-adjust: exact; }
}
)";

// Columns of a table that still fit one column of a before/after pair on a 1400 px window
// (report.html's cells are 50-65 px wide at the pair's font size).
constexpr std::size_t kColumnsInHalf = 11;

// Every block but the page's own headings (levels 1 and 2, which open the header and the sections).
std::string block_html(const Block& b, bool in_header) {
  std::string o;
  switch (b.kind) {
    case Block::Kind::heading: o += fmt::format("<h{0} id=\"{1}\">{2}</h{0}>\n", b.level, esc(b.id), esc(b.text)); break;
    case Block::Kind::paragraph: o += fmt::format("<p>{}</p>\n", esc(b.text)); break;
    case Block::Kind::verdict: o += fmt::format("<p class=\"verdict\">{}</p>\n", esc(b.text)); break;
    case Block::Kind::warning: o += fmt::format("<p class=\"warning\">{}</p>\n", esc(b.text)); break;
    case Block::Kind::list:
      o += in_header ? "<ul class=\"meta\">\n" : "<ul>\n";
      for (const auto& i : b.items) o += fmt::format("<li>{}</li>\n", esc(i));
      o += "</ul>\n";
      break;
    case Block::Kind::definition:
      o += fmt::format("<dl class=\"effect\"><dt>{}</dt><dd>{}</dd></dl>\n", esc(b.text), esc(b.detail));
      break;
    case Block::Kind::table: o += table_html(b.table); break;
    case Block::Kind::figure:
      if (b.svg_html.starts_with("<figure")) o += b.svg_html;  // a figure of its own (trajectory grid)
      else {
        o += "<figure>\n" + b.svg_html;
        if (!b.caption.empty()) o += fmt::format("<figcaption>{}</figcaption>\n", esc(b.caption));
        o += "</figure>\n";
      }
      break;
    case Block::Kind::pair: {
      // A table of many columns does not fit half of a 1400 px window: such a pair stacks its two
      // columns until the window is wide enough for them side by side.
      std::size_t columns = 0;
      for (const auto* side : {&b.before, &b.after})
        for (const auto& x : *side)
          if (x.kind == Block::Kind::table) columns = std::max(columns, x.table.columns.size());
      o += fmt::format("<div class=\"before-after{}\" id=\"{}\">\n", columns > kColumnsInHalf ? " wide" : "",
                       esc(b.id));
      for (const auto* side : {&b.before, &b.after}) {
        o += fmt::format("<div class=\"ba-col ba-{}\">\n", side == &b.before ? "before" : "after");
        for (const auto& x : *side) o += block_html(x, false);
        o += "</div>\n";
      }
      o += "</div>\n";
      break;
    }
  }
  return o;
}

// ---- The charts as files: report.html keeps them inline, report.md links figures/NN-ID.svg ----

// The figure's name: the id of its first element (the figure's, or its first chart's), letters,
// digits, '-' and '_' kept.
std::string figure_id(std::string_view html) {
  const auto at = html.find("id=\"");
  std::string id = at == std::string_view::npos ? std::string("figure")
                                                : std::string(html.substr(at + 4, html.find('"', at + 4) - at - 4));
  for (auto& ch : id)
    if (!std::isalnum(static_cast<unsigned char>(ch)) && ch != '-' && ch != '_') ch = '-';
  return id;
}

// Every figure of the document as a file, numbered in the order report.html shows them; the name
// report.md links for each chart.
struct Figures {
  std::vector<std::pair<std::string, std::string>> files;  // "figures/01-resid-base.svg", its SVG
  std::map<std::string, std::string> name;                  // figure_id -> file name
};

void collect_figures(const std::vector<Block>& blocks, Figures& f) {
  for (const auto& b : blocks) {
    if (b.kind == Block::Kind::pair) {
      collect_figures(b.before, f);
      collect_figures(b.after, f);
    }
    if (b.kind != Block::Kind::figure) continue;
    const std::string id = figure_id(b.svg_html);
    if (f.name.count(id)) continue;
    std::string svg = svg_file(b.svg_html, b.caption);
    if (svg.empty()) continue;
    const std::string file = fmt::format("figures/{:02d}-{}.svg", f.files.size() + 1, id);
    f.name[id] = file;
    f.files.emplace_back(file, std::move(svg));
  }
}

std::string render_html(const Doc& d, const ReportInput& in) {
  std::string o = "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
                  "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n";
  o += fmt::format("<title>chutelab validation: {}</title>\n<style>{}</style>\n</head>\n<body>\n<main>\n",
                   esc(in.baseline->dataset_folder.empty() ? in.baseline->dataset_name : in.baseline->dataset_folder),
                   kCss);
  // Contents from the level-2 headings.
  std::string toc;
  for (const auto& b : d.blocks)
    if (b.kind == Block::Kind::heading && b.level == 2)
      toc += fmt::format("<a href=\"#{}\">{}</a>", esc(b.id), esc(b.text));
  bool toc_done = false;
  bool in_section = false, in_fold = false;
  for (const auto& b : d.blocks) {
    if (b.kind == Block::Kind::heading && b.level == 2) {
      if (!toc_done) {
        o += fmt::format("<nav class=\"toc\">{}</nav>\n</header>\n", toc);
        toc_done = true;
      }
      if (in_fold) o += "</details>\n";
      if (in_section) o += "</section>\n";
      if (b.folded)
        o += fmt::format("<section id=\"{}\">\n<details class=\"fold\"><summary><h2>{}</h2></summary>\n", esc(b.id),
                         esc(b.text));
      else o += fmt::format("<section id=\"{}\">\n<h2>{}</h2>\n", esc(b.id), esc(b.text));
      in_section = true;
      in_fold = b.folded;
    } else if (b.kind == Block::Kind::heading && b.level == 1) {
      o += fmt::format("<header>\n<h1 id=\"{}\">{}</h1>\n", esc(b.id), esc(b.text));
    } else {
      o += block_html(b, !toc_done);
    }
  }
  if (!toc_done) o += "</header>\n";
  if (in_fold) o += "</details>\n";
  if (in_section) o += "</section>\n";
  o += "<footer>Written by chutelab. E = predicted − measured (ASME V&amp;V 20 sign); u_val = the validation "
       "uncertainty of V&amp;V 20 (measurement, numerical and input uncertainties combined). Values outside "
       "tolerance: red, marked ✗, the limit in the tooltip; values more than 2 u_val off: amber."
       "</footer>\n</main>\n</body>\n</html>\n";
  return o;
}

std::string blocks_markdown(const std::vector<Block>& blocks, const Figures& figures) {
  std::string o;
  for (const auto& b : blocks) {
    switch (b.kind) {
      case Block::Kind::heading:
        o += fmt::format("{} {}\n\n", std::string(static_cast<std::size_t>(b.level), '#'), md_esc(b.text));
        break;
      case Block::Kind::paragraph: o += md_esc(b.text) + "\n\n"; break;
      case Block::Kind::verdict: o += "**" + md_esc(b.text) + "**\n\n"; break;
      case Block::Kind::warning: o += "**Warning:** " + md_esc(b.text) + "\n\n"; break;
      case Block::Kind::list:
        for (const auto& i : b.items) o += "- " + md_esc(i) + "\n";
        o += "\n";
        break;
      case Block::Kind::definition: o += fmt::format("**{}**: {}\n\n", md_esc(b.text), md_esc(b.detail)); break;
      case Block::Kind::table: o += table_markdown(b.table); break;
      case Block::Kind::figure: {
        // The chart as the file written beside report.md, its caption under it.
        const std::string what = b.caption.empty() ? "Chart" : b.caption;
        std::string links;
        for (const auto* svg : {&b.svg_html, &b.after_svg_html}) {
          if (svg->empty()) continue;
          const auto it = figures.name.find(figure_id(*svg));
          if (it == figures.name.end()) continue;
          const std::string alt = b.after_svg_html.empty() ? shorten(what, 80) : svg == &b.svg_html ? "before" : "after";
          links += fmt::format("{}![{}]({})", links.empty() ? "" : " ", md_esc(alt), it->second);
        }
        if (links.empty()) o += fmt::format("*{} (in report.html)*\n\n", md_esc(what));
        else o += fmt::format("{}\n\n*{}*\n\n", links, md_esc(what));
        break;
      }
      case Block::Kind::pair:
        if (!b.merged.empty()) o += blocks_markdown(b.merged, figures);
        else o += blocks_markdown(b.before, figures) + blocks_markdown(b.after, figures);
        break;
    }
  }
  return o;
}

}  // namespace

ReportFiles report_files(const ReportInput& in) {
  const Doc d = assemble(in);
  ReportFiles out;
  Figures figures;
  collect_figures(d.blocks, figures);
  out.markdown = blocks_markdown(d.blocks, figures);
  out.html = render_html(d, in);
  out.figures = std::move(figures.files);
  return out;
}

std::string report_markdown(const ReportInput& in) { return report_files(in).markdown; }

std::string report_html(const ReportInput& in) { return render_html(assemble(in), in); }

}  // namespace chutelab::reports
