#define BOOST_TEST_MODULE reports
// The report's content from a small hand-built result: failing cells marked in both renderers,
// a dash where a model predicts nothing, user text escaped, the same bytes for the same inputs,
// and nothing that reaches outside the file.
#include <boost/test/unit_test.hpp>
#include <cmath>
#include <algorithm>
#include <regex>
#include <set>
#include <string>
#include <tuple>
#include <vector>

#include "reports/plain_summary.h"
#include "reports/report.h"
#include "reports/svg.h"

namespace chutelab::test {
namespace {

using validation::Comparison;
using validation::ConditionResult;
using validation::Dataset;
using validation::ValidationResult;

const std::string kNasty = "a<b&c>|*";  // condition name from a user's file

Setup small_setup() {
  Setup s;
  s.name = "hand-made";
  s.source = "unit test";
  s.belt.pulley_diameter = 0.25;
  s.belt.belt_thickness = 0.005;
  s.belt.belt_width = 0.3;
  s.belt.loaded_width = 0.2;
  s.plate.width = 0.4;
  s.plate.height = 0.5;
  s.material.bulk_density = 558.0;
  s.material.friction_plate = 0.27;
  return s;
}

Dataset small_dataset() {
  Dataset d;
  d.dir = "hand-made";
  d.setup = small_setup();
  // Listed out of order: the report sorts by belt speed.
  d.stations.push_back(validation::make_station(d.setup, "V3", 3.0, 41.0 / 3.6, 0.4, 0.25, 0.034));
  d.stations.push_back(validation::make_station(d.setup, kNasty, 2.0, 26.0 / 3.6, 0.3, 0.25, 0.0342));
  d.station_lines.resize(2);
  auto meas = [&](const std::string& c, Quantity q, double v, double u) {
    d.measurements.push_back({c, q, v, u, {}});
  };
  meas(kNasty, Quantity::normal_force, 14.91, 0.068);
  meas(kNasty, Quantity::resultant_force, 15.091, 0.069);
  meas(kNasty, Quantity::exit_velocity, 1.758, 0.003);
  meas(kNasty, Quantity::impact_point_y, 0.0419, 0.0001);
  meas("V3", Quantity::normal_force, 34.996, 0.148);
  meas("V3", Quantity::resultant_force, 35.21, 0.15);
  meas("V3", Quantity::exit_velocity, 1.828, 0.009);
  meas("V3", Quantity::impact_point_y, 0.0589, 0.0003);
  d.trajectory.push_back({kNasty, Boundary::upper, 0.1, 0.1475, 0.001, {}});
  return d;
}

// m1 predicts forces and V_a (V_a only at the first condition); m2 only the impact point.
ValidationResult small_result(const Dataset& d, bool with_tolerance) {
  ValidationResult r;
  r.dataset_name = "hand-made";
  r.models = {"m1", "m2"};
  auto pred = [&](const std::string& c, const std::string& m) -> validation::ModelPrediction& {
    r.predictions.push_back({c, m, {}});
    return r.predictions.back().prediction;
  };
  {
    auto& p = pred(kNasty, "m1");
    p.values[Quantity::normal_force] = 14.4444;
    p.values[Quantity::shear_force] = 3.9;
    p.values[Quantity::resultant_force] = 18.2617;  // +21 %: the failing cell
    p.values[Quantity::exit_velocity] = 0.930998;
    p.notes.push_back("note for <m1> & co");
  }
  pred(kNasty, "m2").values[Quantity::impact_point_y] = 0.0334859;
  {
    auto& p = pred("V3", "m1");
    p.values[Quantity::normal_force] = 34.17;
    p.values[Quantity::shear_force] = 9.22;
    p.values[Quantity::resultant_force] = 35.39;
    // no exit velocity here: the table shows a dash
  }
  pred("V3", "m2").values[Quantity::impact_point_y] = 0.0566;

  for (const auto& m : d.measurements)
    for (const auto& model : r.models) {
      Comparison c;
      c.condition = m.condition;
      c.model = model;
      c.quantity = std::string(name(m.quantity));
      c.q = m.quantity;
      c.scale = info(m.quantity).to_boundary;
      c.measured = m.value;
      c.uncertainty = m.uncertainty;
      c.predicted = r.prediction(m.condition, model)->prediction.values[m.quantity];
      if (with_tolerance && c.predicted) {
        c.verdict.checked = true;
        if (model == "m1" && m.quantity == Quantity::resultant_force && m.condition == kNasty) {
          c.verdict.passed = false;
          c.verdict.limit = "|rel| 0.210 > 0.150";
        }
      }
      r.comparisons.push_back(c);
    }
  r.acceptance_checked = with_tolerance;
  r.acceptance_failed = with_tolerance;
  r.summary.push_back({"m1", "resultant_force_N", 2, 2.2, 34.0, 0.21, with_tolerance ? std::optional(false) : std::nullopt});
  r.summary.push_back({"m2", "impact_point_y_mm", 2, 5.6, 40.0, 0.2, std::nullopt});
  return r;
}

std::string section(const std::string& text, const std::string& from, const std::string& to) {
  const auto a = text.find(from);
  BOOST_REQUIRE_MESSAGE(a != std::string::npos, "missing: " + from);
  const auto b = text.find(to, a + from.size());
  return text.substr(a, b == std::string::npos ? std::string::npos : b - a);
}

std::string line_starting(const std::string& text, const std::string& start) {
  const auto a = text.find("\n" + start);
  BOOST_REQUIRE_MESSAGE(a != std::string::npos, "no line starting with " + start);
  const auto b = text.find('\n', a + 1);
  return text.substr(a + 1, b - a - 1);
}

struct Fixture {
  Dataset d = small_dataset();
  ValidationResult r = small_result(d, true);
  reports::ReportInput in() const {
    reports::ReportInput i;
    i.dataset = &d;
    i.baseline = &r;
    i.notes = {"fitted on 3 values: chi^2 10 -> 2"};
    return i;
  }
};

}  // namespace

BOOST_FIXTURE_TEST_CASE(failing_cell_is_marked_in_markdown_and_html, Fixture) {
  const auto md = reports::report_markdown(in());
  const auto html = reports::report_html(in());
  // R of m1 at the first condition: 18.26 N, 21 % off, outside the tolerance.
  const auto t4 = section(md, "**Plate forces", "**Stream");
  BOOST_TEST(t4.find("**18.26 \u2717**") != std::string::npos, t4);
  // Every failed value is listed once, under "Outside tolerance", with its limit; no entities.
  const auto failures = section(md, "## Outside tolerance", "\n## ");
  BOOST_TEST(failures.find("| R plate resultant force |") != std::string::npos, failures);
  BOOST_TEST(failures.find("\\|rel\\| 0.210 > 0.150") != std::string::npos, failures);
  BOOST_TEST(md.find("&gt;") == std::string::npos);
  BOOST_TEST(html.find("class=\"num fail\" title=\"outside tolerance: |rel| 0.210 &gt; 0.150") != std::string::npos);
  // Exactly the failing cells are marked: R and its error column.
  const auto t4html = section(html, "<table class=\"data\" id=\"table4-base\"", "</table>");
  std::size_t n = 0;
  for (auto p = t4html.find("fail\""); p != std::string::npos; p = t4html.find("fail\"", p + 1)) ++n;
  BOOST_TEST(n == 2u);
  // The summary says the model is not within tolerance.
  BOOST_TEST(md.find("**no \u2717**") != std::string::npos);
}

// y_R is a height whose zero is the pulley's centre: the summary gives it no relative error in %.
BOOST_FIXTURE_TEST_CASE(a_height_has_no_relative_error, Fixture) {
  const auto md = reports::report_markdown(in());
  const auto summary = section(md, "**Summary per model and quantity", "\n## ");
  const auto yr = line_starting(summary, "| m2 | y\\_R");
  BOOST_TEST(yr.find("| 5.60 mm | 40.0 | \u2014 |") != std::string::npos, yr);
  BOOST_TEST(line_starting(summary, "| m1 | R plate").find("| 21.0 |") != std::string::npos, summary);
  BOOST_TEST(summary.find("Heights (y\\_R, the stream boundaries) have no relative error") != std::string::npos, summary);
}

BOOST_FIXTURE_TEST_CASE(no_tolerance_means_no_marks, Fixture) {
  r = small_result(d, false);
  const auto html = reports::report_html(in());
  BOOST_TEST(html.find("class=\"num fail\"") == std::string::npos);
  BOOST_TEST(reports::report_markdown(in()).find("\u2717**") == std::string::npos);
}

BOOST_FIXTURE_TEST_CASE(dash_where_a_model_predicts_nothing, Fixture) {
  const auto md = reports::report_markdown(in());
  const auto t5 = section(md, "**Stream velocities", "\n\n\n");
  // Row V3: m1 predicts no V_a there.
  const auto row = line_starting(t5, "| V3 |");
  BOOST_TEST(row.find("| 1.828 ± 0.009 | \u2014 |") != std::string::npos, row);
  // m2 predicts no force at all: left out of Table 4 with a note, not a column of dashes.
  const auto t4 = section(md, "**Plate forces", "**Stream");
  BOOST_TEST(t4.find("m2 R") == std::string::npos);
  BOOST_TEST(t4.find("Not shown: m2") != std::string::npos);
  // Shear force is not measured: the measured column shows a dash.
  const auto row4 = line_starting(t4, "| V3 |");
  BOOST_TEST(row4.find("| 35.00 ± 0.15 | \u2014 |") != std::string::npos, row4);
}

BOOST_FIXTURE_TEST_CASE(user_text_is_escaped, Fixture) {
  const auto md = reports::report_markdown(in());
  const auto html = reports::report_html(in());
  BOOST_TEST(html.find("a<b&c>") == std::string::npos);
  BOOST_TEST(html.find("a&lt;b&amp;c&gt;|*") != std::string::npos);
  BOOST_TEST(html.find("note for &lt;m1&gt; &amp; co") != std::string::npos);
  // report.md escapes with backslashes where a tag or an entity could start, never with entities.
  BOOST_TEST(md.find("a<b&c>") == std::string::npos);
  BOOST_TEST(md.find("a\\<b&c>\\|\\*") != std::string::npos);
  for (const char* entity : {"&lt;", "&gt;", "&amp;", "&quot;"}) BOOST_TEST(md.find(entity) == std::string::npos, entity);
  // The nasty name sorts first (2 m/s) and its table row stays one row of the right width.
  const auto t4 = section(md, "**Plate forces", "**Stream");
  const auto header = line_starting(t4, "| condition");
  const auto row = line_starting(t4, "| a\\<");
  auto cells = [](const std::string& s) {
    std::size_t n = 0;
    for (std::size_t i = 0; i < s.size(); ++i) n += s[i] == '|' && (i == 0 || s[i - 1] != '\\');
    return n;
  };
  BOOST_TEST(cells(row) == cells(header));
  BOOST_TEST(md.find("| a\\<") < md.find("| V3 |"));
}

BOOST_FIXTURE_TEST_CASE(same_inputs_same_bytes, Fixture) {
  const auto html1 = reports::report_html(in());
  const auto md1 = reports::report_markdown(in());
  // A fresh copy of the same inputs (different addresses) renders identically.
  const Dataset d2 = small_dataset();
  const ValidationResult r2 = small_result(d2, true);
  reports::ReportInput i2 = in();
  i2.dataset = &d2;
  i2.baseline = &r2;
  BOOST_TEST(reports::report_html(i2) == html1);
  BOOST_TEST(reports::report_markdown(i2) == md1);
  BOOST_TEST(reports::report_html(in()) == html1);
}

BOOST_FIXTURE_TEST_CASE(html_is_self_contained, Fixture) {
  const auto html = reports::report_html(in());
  for (const char* s : {"<script", "<link", "http://", "https://", "@import", "src=", "<img"})
    BOOST_TEST(html.find(s) == std::string::npos, s);
  for (auto p = html.find("url("); p != std::string::npos; p = html.find("url(", p + 1))
    BOOST_TEST(html.substr(p, 5) == "url(#");  // only references to the page's own clip paths
  BOOST_TEST(html.find("<svg") != std::string::npos);
  BOOST_TEST(reports::report_markdown(in()).find("<svg") == std::string::npos);
  // Axis labels with units on the pictures.
  BOOST_TEST(html.find(">x (mm)</text>") != std::string::npos);
  BOOST_TEST(html.find(">y (mm)</text>") != std::string::npos);
  BOOST_TEST(html.find("plate resultant force R (N)") != std::string::npos);
  BOOST_TEST(html.find(">E/u_val (–)</text>") != std::string::npos);
}

BOOST_FIXTURE_TEST_CASE(before_after_and_diagnosis_sections, Fixture) {
  ValidationResult after = small_result(d, false);
  after.effects = {"air_drag=0.5 (fitted)"};
  validation::DiagnosisResult g;
  g.dataset = "hand-made";
  g.models = {"m1", "m2"};
  g.verdict = "Missing effect: air_drag <really>.";
  g.failure_summary = {"m1 over-predicts R_s"};
  validation::EffectFit f;
  f.effects = {"air_drag"};
  f.parameters = {"drag_coefficient"};
  f.estimate = {0.5};
  f.uncertainty = {0.03};
  f.chi2_before = 100;
  f.chi2_after = 20;
  f.significant = true;
  f.rank = 1;
  g.singles.push_back(f);
  g.any_significant = true;
  g.caveats = {"only the library's effects were tried"};
  auto i = in();
  i.with_effects = &after;
  i.diagnosis = &g;
  i.effects.push_back({"air_drag", "drag_coefficient", "", "F = c v^2 <drag>", "Crowe", 0.5, 0.03, true});
  const auto html = reports::report_html(i);
  const auto md = reports::report_markdown(i);
  for (const char* id : {"id=\"missing\"", "id=\"before-after\"", "id=\"ranking-chart\"", "id=\"rms-before-after\"",
                         "id=\"table4-effects\"", "id=\"resid-effects-pair\"", "id=\"traj-effects\"",
                         "id=\"change-in-words\""})
    BOOST_TEST(html.find(id) != std::string::npos, id);
  BOOST_TEST(html.find("Missing effect: air_drag &lt;really&gt;.") != std::string::npos);
  BOOST_TEST(html.find("F = c v^2 &lt;drag&gt;") != std::string::npos);
  BOOST_TEST(md.find("## What is missing") != std::string::npos);
  // The story first: the verdict, where the models fail, the before and after, then the diagnosis.
  BOOST_TEST(md.find("**Missing effect: air\\_drag \\<really>.**") < md.find("## Where the models fail"));
  BOOST_TEST(md.find("## Where the models fail") < md.find("## Before and after adding air\\_drag"));
  BOOST_TEST(md.find("## Before and after adding air\\_drag") < md.find("## What is missing"));
  BOOST_TEST(md.find("## What is missing") < md.find("## Plate forces"));
  BOOST_TEST(md.find("## Plate forces") < md.find("## Appendix: validation uncertainty (V&V 20)"));
  BOOST_TEST(md.find("With effects: air\\_drag=0.5 (fitted)") != std::string::npos);
  BOOST_TEST(md.find("only the library's effects were tried") != std::string::npos);
}

// Engineering words first: the ranking chart and table speak in % of the misfit explained and "beyond
// chance"; chi-square, BIC and p are under "How sure is this?", a section report.html shows closed,
// and never on the first screen (the header, the verdict and the first chart's section).
BOOST_FIXTURE_TEST_CASE(statistics_only_under_how_sure_is_this, Fixture) {
  ValidationResult after = small_result(d, false);
  after.effects = {"air_drag=0.5 (fitted)"};
  validation::DiagnosisResult g;
  g.dataset = "hand-made";
  g.models = {"m1", "m2"};
  g.n_data = 20;
  g.chi2_baseline = 100;
  g.baseline_p_value = 3e-12;
  g.verdict = "Missing effect: air_drag.";
  g.evidence = "chi^2 100.0 -> 20.0 for 20 data, delta BIC -77.0, p (adjusted) 1e-15";
  g.failure_summary = {"m1 over-predicts R_s by 7.2 % (2.45 N)"};
  // Findings and caveats in words stay with the ranking; those in statistics move under "How sure is this?".
  g.findings = {"Check this reading: V2-26 R_s reads 2.335, 94 % above the best explanation.",
                "The readings scatter 2.4 times more than stated (chi^2/dof over 46 degrees of freedom, p = 5e-34)."};
  g.caveats = {"Only the effects in chutelab's library were tried.",
               "Significance: likelihood-ratio test per candidate, Bonferroni-corrected over 19 candidates."};
  validation::EffectFit f;
  f.effects = {"air_drag"};
  f.parameters = {"drag_coefficient"};
  f.estimate = {0.5};
  f.uncertainty = {0.03};
  f.chi2_before = 100;
  f.chi2_after = 20;
  f.delta_bic = -77;
  f.explained_fraction = 0.875;
  f.p_adjusted = 1e-15;
  f.significant = true;
  f.rank = 1;
  g.singles.push_back(f);
  validation::EffectFit weak = f;
  weak.effects = {"belt_slip"};
  weak.parameters = {"slip_fraction"};
  weak.chi2_after = 96;
  weak.delta_bic = 1;
  weak.explained_fraction = 0.04;
  weak.p_adjusted = 0.6;
  weak.significant = false;
  weak.rank = 2;
  g.singles.push_back(weak);
  g.any_significant = true;
  auto i = in();
  i.with_effects = &after;
  i.diagnosis = &g;
  i.effects.push_back({"air_drag", "drag_coefficient", "", "", "", 0.5, 0.03, true});
  const auto html = reports::report_html(i);
  const auto md = reports::report_markdown(i);
  auto between = [](const std::string& s, const std::string& a, const std::string& b) {
    const auto from = s.find(a);
    BOOST_TEST_REQUIRE(from != std::string::npos, a);
    const auto to = s.find(b, from);
    BOOST_TEST_REQUIRE(to != std::string::npos, b);
    return s.substr(from, to - from);
  };
  const std::vector<std::string> statistics = {"χ²", "chi^2", "BIC", " p = ", "p (adjusted", "Bonferroni"};
  // The chart: bars in % (87.5 % of the misfit; 4 %), an axis in words, tooltips without statistics.
  const std::string chart = between(html, "id=\"ranking-chart\"", "</svg>");
  BOOST_TEST(chart.find(">share of the misfit beyond noise explained with the effect fitted (%)</text>") != std::string::npos);
  BOOST_TEST(chart.find(">88 % explained</text>") != std::string::npos, chart);
  BOOST_TEST(chart.find(">4 % explained</text>") != std::string::npos);
  BOOST_TEST(chart.find(">100</text>") != std::string::npos);  // the axis ends at the whole misfit
  BOOST_TEST(chart.find("could be chance") != std::string::npos);
  // The bar's length is its share of the axis (0 to 100 %).
  {
    std::smatch m;
    const std::regex bar("<rect x=\"([0-9.]+)\" y=\"[0-9.]+\" width=\"([0-9.]+)\"[^>]*class=\"bar\"");
    BOOST_TEST_REQUIRE(std::regex_search(chart, m, bar));
    const double w_best = std::stod(m[2]);
    const std::string rest = m.suffix();
    BOOST_TEST_REQUIRE(std::regex_search(rest, m, bar));
    BOOST_TEST(std::stod(m[2]) / w_best == 0.04 / 0.875, boost::test_tools::tolerance(0.05));
  }
  // Neither the chart, nor the ranking section, nor the first screen carries a statistic.
  const std::string section = between(md, "## What is missing", "## How sure is this?");
  const std::string first_screen = md.substr(0, md.find("\n## ", md.find("## Where the models fail") + 1));
  for (const auto& w : statistics) {
    BOOST_TEST(chart.find(w) == std::string::npos, w);
    BOOST_TEST(section.find(w) == std::string::npos, w << " in:\n" << section);
    BOOST_TEST(first_screen.find(w) == std::string::npos, w << " in:\n" << first_screen);
  }
  BOOST_TEST(section.find("| misfit explained (%) | beyond chance |") != std::string::npos, section);
  // Under "How sure is this?": the evidence, the baseline's chi-square and every candidate's statistics.
  const std::string sure = md.substr(md.find("## How sure is this?"));
  BOOST_TEST(sure.find(g.evidence) != std::string::npos);
  BOOST_TEST(sure.find("With the uncertainties as stated, χ² of the models as they are is 100.0 for 20 data") != std::string::npos, sure);
  BOOST_TEST(sure.find("| χ² after | Δχ² | ΔBIC |") != std::string::npos, sure);
  BOOST_TEST(sure.find("| 80.0 | -77.0 |") != std::string::npos, sure);
  BOOST_TEST(section.find("Check this reading: V2-26 R\\_s reads 2.335") != std::string::npos, section);
  BOOST_TEST(section.find("Only the effects in chutelab's library were tried.") != std::string::npos, section);
  BOOST_TEST(sure.find("The readings scatter 2.4 times more than stated") != std::string::npos, sure);
  BOOST_TEST(sure.find("Significance: likelihood-ratio test per candidate") != std::string::npos, sure);
  BOOST_TEST(html.find("<section id=\"how-sure\">\n<details class=\"fold\"><summary><h2>How sure is this?</h2>") !=
             std::string::npos);
}

// Every chart of report.html is also an SVG file that report.md links, "figures/NN-ID.svg": one file a
// figure (a pair's two columns two files, linked side by side), each standalone (XML prolog, SVG
// namespace, its caption as title), no "(see report.html)" left, the same bytes for the same inputs.
BOOST_FIXTURE_TEST_CASE(every_chart_is_a_file_report_md_links, Fixture) {
  ValidationResult after = small_result(d, false);
  after.effects = {"air_drag=0.5 (fitted)"};
  auto i = in();
  i.with_effects = &after;
  i.effects.push_back({"air_drag", "drag_coefficient", "", "drag", "Crowe", 0.5, 0.03, true});
  const reports::ReportInput plain = in();
  for (const reports::ReportInput* input : {static_cast<const reports::ReportInput*>(&i), &plain}) {
    const bool pair = input == &i;
    const reports::ReportInput& x = *input;
    const reports::ReportFiles f = reports::report_files(x);
    BOOST_TEST(f.markdown == reports::report_markdown(x));
    BOOST_TEST(f.html == reports::report_html(x));
    BOOST_TEST(f.markdown.find("see report.html") == std::string::npos);
    BOOST_TEST(f.markdown.find("in report.html)") == std::string::npos);
    // As many files as report.html has figures.
    std::size_t figures = 0;
    for (auto p = f.html.find("<figure"); p != std::string::npos; p = f.html.find("<figure", p + 1)) ++figures;
    BOOST_TEST(f.figures.size() == figures);
    BOOST_TEST(figures >= (pair ? 6u : 3u));
    std::set<std::string> names, linked;
    for (const auto& [name, svg] : f.figures) {
      BOOST_TEST_CONTEXT(name) {
        BOOST_TEST(std::regex_match(name, std::regex(R"(figures/[0-9]{2}-[A-Za-z0-9_-]+\.svg)")));
        BOOST_TEST(names.insert(name).second);
        BOOST_TEST(svg.starts_with("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<svg xmlns=\"http://www.w3.org/2000/svg\" "));
        BOOST_TEST(svg.find("<title>") != std::string::npos);
        BOOST_TEST(svg.ends_with("</svg>\n"));
        std::size_t open = 0, close = 0;
        for (auto p = svg.find("<svg "); p != std::string::npos; p = svg.find("<svg ", p + 1)) ++open;
        for (auto p = svg.find("</svg>"); p != std::string::npos; p = svg.find("</svg>", p + 1)) ++close;
        BOOST_TEST(open == close);
      }
    }
    static const std::regex link(R"(!\[[^\]]*\]\((figures/[^)]+)\))");
    for (std::sregex_iterator it(f.markdown.begin(), f.markdown.end(), link), end; it != end; ++it)
      linked.insert((*it)[1].str());
    BOOST_TEST((linked == names));
    if (pair) {
      BOOST_TEST(f.markdown.find("![before](figures/") != std::string::npos);
      BOOST_TEST(f.markdown.find(".svg) ![after](figures/") != std::string::npos);
    }
    // The trajectories' legend and panels, laid out in one picture.
    const auto traj = std::find_if(f.figures.begin(), f.figures.end(), [](const auto& p) {
      return p.first.find("-traj-base.svg") != std::string::npos;
    });
    BOOST_TEST_REQUIRE((traj != f.figures.end()));
    BOOST_TEST(traj->second.find("<svg x=\"0.0\" y=\"0.0\" class=\"plot traj-legend\"") != std::string::npos);
    BOOST_TEST(reports::report_files(x).figures == f.figures);
  }
}

// With effects, each section's before/after pair is one element of two columns, the models as they
// are first; the page's style lays them side by side and stacks them on narrow screens (and a pair
// of wide tables below 1800 px). The two residual charts of the detail share one frame (same size:
// their panels line up), a compact before/after chart heads "Before and after", and report.md puts
// the numbers in one table with before and after columns, a column that did not change shown once.
BOOST_FIXTURE_TEST_CASE(before_and_after_side_by_side, Fixture) {
  ValidationResult after = small_result(d, true);
  after.effects = {"air_drag=0.5 (fitted)"};
  after.summary[0].rms_normalised_error = 1.5;  // m1's R: 34.0 before
  // The effect moves every prediction by 1 %.
  for (auto& p : after.predictions)
    for (Quantity q : kAllQuantities)
      if (p.prediction.values[q]) *p.prediction.values[q] *= 1.01;
  for (auto& cmp : after.comparisons)
    if (cmp.predicted) *cmp.predicted *= 1.01;
  validation::DiagnosisResult g;
  g.dataset = "hand-made";
  g.models = {"m1", "m2"};
  g.verdict = "Missing effect: air_drag.";
  auto i = in();
  i.with_effects = &after;
  i.diagnosis = &g;
  i.effects.push_back({"air_drag", "drag_coefficient", "", "drag", "", 0.5, 0.03, true});
  const auto html = reports::report_html(i);
  const auto md = reports::report_markdown(i);

  // The pair element: two columns, before then after, each with its own table or chart.
  auto pair_of = [&](const std::string& id) { return section(html, "id=\"" + id + "\">", "<section"); };
  for (const auto& [pair, base, effects] :
       std::vector<std::tuple<std::string, std::string, std::string>>{{"summary-pair", "summary-table-base", "summary-table-effects"},
                                                                      {"forces-pair", "table4-base", "table4-effects"},
                                                                      {"velocities-pair", "table5-base", "table5-effects"},
                                                                      {"trajectories-pair", "traj-base", "traj-effects"},
                                                                      {"trends-pair", "resid-base-pair", "resid-effects-pair"}}) {
    const std::string p = pair_of(pair);
    const auto col_b = p.find("<div class=\"ba-col ba-before\">"), col_a = p.find("<div class=\"ba-col ba-after\">");
    BOOST_TEST_REQUIRE((col_b != std::string::npos && col_a != std::string::npos && col_b < col_a), pair);
    const auto at_b = p.find("id=\"" + base + "\""), at_a = p.find("id=\"" + effects + "\"");
    BOOST_TEST((at_b > col_b && at_b < col_a), pair << ": " << base << " in the first column");
    BOOST_TEST((at_a != std::string::npos && at_a > col_a), pair << ": " << effects << " in the second column");
    BOOST_TEST(p.find("ba-col", col_a + std::string("<div class=\"ba-col").size()) == std::string::npos,
               pair << ": two columns");
  }
  BOOST_TEST(html.find("grid-template-columns: minmax(0, 1fr) minmax(0, 1fr)") != std::string::npos);
  BOOST_TEST(html.find("@media (max-width: 1199px) { .before-after { display: block;") != std::string::npos);
  // One frame for both residual charts.
  auto svg_size = [&](const std::string& id) {
    const std::string tag = section(html, "<svg class=\"plot residual-chart\" id=\"" + id + "\"", ">");
    return tag.substr(tag.find("viewBox"));
  };
  BOOST_TEST(svg_size("resid-base-pair") == svg_size("resid-effects-pair"));
  BOOST_TEST(svg_size("resid-base-pair").find("640") != std::string::npos);
  // The compact chart in "Before and after".
  const std::string missing = section(html, "<section id=\"before-after\">", "</section>");
  BOOST_TEST(missing.find("id=\"resid-change\"") != std::string::npos);
  BOOST_TEST(missing.find("class=\"residual-change-panel\"") != std::string::npos);

  // report.md: one summary table, before and after side by side in its columns.
  const auto summary = section(md, "**Summary per model and quantity — before and after**", "\n\n\n");
  BOOST_TEST(summary.find("| RMS E/u\\_val before | RMS E/u\\_val after |") != std::string::npos, summary);
  BOOST_TEST(line_starting(summary, "| m1 |").find("| 34.0 | 1.50 |") != std::string::npos, summary);
  BOOST_TEST(summary.find("| n before |") == std::string::npos, summary);  // unchanged: once
  BOOST_TEST(md.find("**Summary per model and quantity**") == std::string::npos);
  const auto t4 = section(md, "**Plate forces: measured and predicted (cf. the reference study's Table 4) — before and after**", "\n\n\n");
  BOOST_TEST(t4.find("| measured R (N) |") != std::string::npos, t4);
  BOOST_TEST(t4.find("| m1 R (N) before | m1 R (N) after |") != std::string::npos, t4);
}

// Without effects there is nothing to pair: the page has no pair element and report.md no merged table.
BOOST_FIXTURE_TEST_CASE(no_pairs_without_effects, Fixture) {
  const auto html = reports::report_html(in());
  BOOST_TEST(html.find("<div class=\"before-after\"") == std::string::npos);
  BOOST_TEST(html.find("id=\"resid-change\"") == std::string::npos);
  BOOST_TEST(reports::report_markdown(in()).find("before and after") == std::string::npos);
}

// A point cloud (a DEM's particles) is dots coloured on one scale shared by every panel, never a
// polyline through 3000 particles; the reference study's findings appear when given.
BOOST_FIXTURE_TEST_CASE(point_clouds_are_dots_with_a_colour_bar, Fixture) {
  validation::Curve cloud{"particles", {}, validation::Curve::Kind::points, {}, "speed (m/s)"};
  for (int i = 0; i < 50; ++i) {
    cloud.points.emplace_back(0.005 * i, 0.15 - 0.001 * i);
    cloud.value.push_back(0.1 * i);
  }
  for (auto& p : r.predictions)
    if (p.model == "m1") p.prediction.curves.push_back(cloud);
  std::vector<validation::ReferenceFinding> findings(1);
  findings[0].number = 1;
  findings[0].statement = "a finding";
  findings[0].status = validation::FindingStatus::partly;
  findings[0].claims = {{"claim one", true, true, "numbers one"}, {"claim two", true, false, "numbers two"}};
  auto i = in();
  i.findings = &findings;
  const std::string html = reports::report_html(i), md = reports::report_markdown(i);
  BOOST_TEST(html.find("class=\"cloud\"") != std::string::npos);
  BOOST_TEST(html.find("<title>m1: particles</title>") == std::string::npos);  // not drawn as a line
  BOOST_TEST(html.find("4.90 speed (m/s)") != std::string::npos);               // colour bar to the max
  BOOST_TEST(html.find("#fde725") != std::string::npos);                        // fastest bin used
  BOOST_TEST(md.find("The reference study's findings") != std::string::npos);
  BOOST_TEST(md.find("partly reproduced") != std::string::npos);
  BOOST_TEST(md.find("numbers two") != std::string::npos);
}

// What this dataset cannot test does not apply to the rig: no row, one note naming it; a dataset that
// can test nothing of the reference study gets no section at all.
BOOST_FIXTURE_TEST_CASE(untestable_findings_are_left_out, Fixture) {
  std::vector<validation::ReferenceFinding> findings(2);
  findings[0].number = 2;
  findings[0].statement = "a finding";
  findings[0].status = validation::FindingStatus::reproduced;
  findings[0].claims = {{"claim tested", true, true, "numbers one"}, {"claim of the dem", false, false, "the dem model was not run"}};
  findings[1].number = 3;
  findings[1].statement = "a finding of the dem";
  findings[1].status = validation::FindingStatus::not_testable;
  findings[1].claims = {{"claim three", false, false, "the dem model was not run"},
                        {"claim four", false, false, "no sensitivity study given"}};
  auto i = in();
  i.findings = &findings;
  const std::string md = reports::report_markdown(i), html = reports::report_html(i);
  const auto sec = section(md, "## The reference study's findings", "\n## ");
  BOOST_TEST(sec.find("claim tested") != std::string::npos, sec);
  for (const auto* text : {&md, &html}) {
    for (const char* gone : {"claim of the dem", "claim three", "claim four", "untestable", "a finding of the dem"})
      BOOST_TEST(text->find(gone) == std::string::npos, gone);
  }
  BOOST_TEST(sec.find("Not testable on this dataset, so left out: finding 3 and one claim of finding 2 (the dem model "
                      "was not run; no sensitivity study given).") != std::string::npos, sec);
  // Nothing testable: no section.
  findings.erase(findings.begin());
  BOOST_TEST(reports::report_markdown(i).find("The reference study's findings") == std::string::npos);
  BOOST_TEST(reports::report_html(i).find("id=\"findings\"") == std::string::npos);
}

BOOST_AUTO_TEST_CASE(nice_ticks_land_on_round_numbers) {
  const auto t = reports::nice_ticks(0.0, 63.3, 6);
  BOOST_TEST(t.step == 10.0);
  BOOST_TEST(t.hi == 70.0);
  BOOST_TEST(t.label(t.values[1]) == "10");
  const auto s = reports::nice_ticks(-0.013, 0.042, 5);
  BOOST_TEST(s.step == 0.01, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(s.label(-0.0) == "0.00");
  BOOST_TEST(reports::fixed(-0.0004, 2) == "0.00");
  const auto l = reports::log_ticks(0.9, 120.0);
  BOOST_TEST(l.lo == 0.1);
  BOOST_TEST(l.hi == 1000.0);
  BOOST_TEST(l.label(100.0) == "100");
}

}  // namespace chutelab::test

namespace chutelab::test {

// The V&V 20 section: the parts of u_val per prediction, and in words which were not estimated.
BOOST_AUTO_TEST_CASE(vv20_section_shows_parts_and_says_what_was_not_estimated) {
  Dataset d = small_dataset();
  ValidationResult r = small_result(d, false);
  reports::ReportInput in;
  in.dataset = &d;
  in.baseline = &r;
  {
    const std::string md = reports::report_markdown(in);
    const std::string s = section(md, "## Appendix: validation uncertainty (V&V 20)", "\n## ");
    BOOST_TEST(s.find("u\\_input not estimated: the dataset states no input uncertainties") != std::string::npos, s);
    BOOST_TEST(s.find("u\\_num statistical part not estimated") == std::string::npos, s);  // m1, m2 unknown: silent
  }
  // Stated input uncertainties and a model with both u_num parts on R_n at V3.
  d.input_uncertainty.assign(d.stations.size(), {});
  d.input_uncertainty[0].belt_speed = 0.02;
  for (auto& c : r.comparisons)
    if (c.predicted) {
      c.u_input = 0.4 / c.scale;  // 0.4 in the quantity's unit
      if (c.model == "m1" && c.condition == "V3" && c.q == Quantity::normal_force) {
        c.prediction_uncertainty = 0.3;
        c.u_num_disc = 1.2;
      }
    }
  const std::string md = reports::report_markdown(in);
  const std::string s = section(md, "## Appendix: validation uncertainty (V&V 20)", "\n## ");
  BOOST_TEST(s.find("u\\_input not estimated") == std::string::npos, s);
  // V3, m1, R_n: E = 34.17 - 34.996 = -0.826; u_val = sqrt(0.148^2 + 0.3^2 + 1.2^2 + 0.4^2) = 1.3084 (three significant digits of the largest, 1.31).
  const std::string row = line_starting(s, "| V3 | m1 | R\\_n (N) |");
  BOOST_TEST(row.find("| -0.83 | 0.15 | 0.30 | 1.20 | 0.40 | 1.31 | 0.63 |") != std::string::npos, row);
  const std::string html = reports::report_html(in);
  BOOST_TEST(html.find("id=\"vv20-table\"") != std::string::npos);
}

}  // namespace chutelab::test

namespace chutelab::test {

// The plain words judge each model on its own values too: a model that agrees is named as agreeing,
// and one that misses is never hidden behind "the models agree" because another model was judged
// first (the DEM after the analytical models, in chutelab's model order).
namespace {

// Every measured value predicted by each model at measured x (1 + offset[model]).
ValidationResult offset_result(const Dataset& d, const std::vector<std::pair<std::string, double>>& models) {
  ValidationResult r;
  r.dataset_name = "hand-made";
  for (const auto& [m, f] : models) r.models.push_back(m);
  for (const auto& s : d.stations)
    for (const auto& [m, f] : models) r.predictions.push_back({s.condition, m, {}});
  for (const auto& meas : d.measurements)
    for (const auto& [m, f] : models) {
      Comparison c;
      c.condition = meas.condition;
      c.model = m;
      c.quantity = std::string(name(meas.quantity));
      c.q = meas.quantity;
      c.scale = info(meas.quantity).to_boundary;
      c.measured = meas.value;
      c.uncertainty = meas.uncertainty;
      c.predicted = meas.value * (1.0 + f);
      r.comparisons.push_back(c);
    }
  return r;
}

std::string joined(const std::vector<std::string>& s) {
  std::string o;
  for (const auto& x : s) o += x + "\n";
  return o;
}

}  // namespace

BOOST_AUTO_TEST_CASE(plain_words_name_the_model_that_agrees_and_the_one_that_misses) {
  const Dataset d = small_dataset();
  // 1e-4 of the value is within every stated uncertainty here (the smallest, u/value, is 2.4e-3);
  // 20 % is far outside all of them.
  for (const auto& models : {std::vector<std::pair<std::string, double>>{{"m1", 1e-4}, {"m2", 0.2}},
                             std::vector<std::pair<std::string, double>>{{"m2", 0.2}, {"m1", 1e-4}}}) {
    const ValidationResult r = offset_result(d, models);
    reports::ReportInput in;
    in.dataset = &d;
    in.baseline = &r;
    const auto words = reports::in_short(in);
    BOOST_TEST_CONTEXT(joined(words)) {
      BOOST_TEST_REQUIRE(words.size() >= 2u);
      BOOST_TEST(words[0].starts_with("m1 agrees with the measurements within the stated uncertainties (RMS E/u_val 0.0"));
      BOOST_TEST(words[1].starts_with("As it is, m2 puts the "));
      BOOST_TEST(words[1].find("20.0 % high on average") != std::string::npos);
      BOOST_TEST(joined(words).find("the models agree") == std::string::npos);
    }
  }
  // Both agree: one sentence for both.
  const ValidationResult r = offset_result(d, {{"m1", 1e-4}, {"m2", -1e-4}});
  reports::ReportInput in;
  in.dataset = &d;
  in.baseline = &r;
  const auto words = reports::in_short(in);
  BOOST_TEST_REQUIRE(words.size() == 1u);
  BOOST_TEST(words[0].starts_with("As they are, the models agree with the measurements"), words[0]);
}

// Highlighted are exactly the predicted cells more than 2 u_val from their measurement: every cell of
// Tables 4 and 5 whose tip gives E/u_val is marked "beyond" if and only if |E/u_val| > 2.
BOOST_AUTO_TEST_CASE(exactly_the_values_beyond_two_u_val_are_highlighted) {
  const Dataset d = small_dataset();
  // m3's 0.7 % puts its values between 1.4 and 4.1 u_val: a threshold of 1 or 3 would be caught.
  const ValidationResult r = offset_result(d, {{"m1", 1e-4}, {"m2", 0.2}, {"m3", 0.007}});
  reports::ReportInput in;
  in.dataset = &d;
  in.baseline = &r;
  const std::string html = reports::report_html(in);
  int beyond = 0, within = 0, just_within = 0, just_beyond = 0;
  for (const char* id : {"table4-base", "table5-base"}) {
    const auto at = html.find(std::string("id=\"") + id + "\"");
    BOOST_REQUIRE_MESSAGE(at != std::string::npos, id);
    const std::string table = html.substr(at, html.find("</table>", at) - at);
    static const std::regex cell(R"re(<td class="([^"]*)" title="[^"]*E/u_val ([-+0-9.]+)[^"]*">)re");
    for (std::sregex_iterator it(table.begin(), table.end(), cell), end; it != end; ++it) {
      const bool marked = (*it)[1].str().find("beyond") != std::string::npos;
      const double z = std::stod((*it)[2].str());
      BOOST_TEST(marked == (std::abs(z) > 2.0), id << ": " << it->str());
      ++(marked ? beyond : within);
      if (std::abs(z) > 1.0 && std::abs(z) <= 2.0) ++just_within;
      if (std::abs(z) > 2.0 && std::abs(z) < 5.0) ++just_beyond;
    }
  }
  BOOST_TEST(beyond > 0);
  BOOST_TEST(within > 0);
  BOOST_TEST(just_within >= 1);
  BOOST_TEST(just_beyond >= 1);
  // The Markdown marks the same values.
  BOOST_TEST(reports::report_markdown(in).find("= the value is more than 2 u_val from the measurement") !=
             std::string::npos);
}

}  // namespace chutelab::test

namespace chutelab::test {

// The plate's maps in the units an engineer reads: pressures in kPa (a colour bar never says
// "4.26e+03 Pa"), wear in µm/h (never "um/h"), numbers in fixed notation.
BOOST_AUTO_TEST_CASE(plate_maps_speak_kpa_and_micrometres_per_hour) {
  const Dataset d = small_dataset();
  ValidationResult r = small_result(d, false);
  validation::SurfaceMap m;
  m.name = "plate";
  // Two cells of a 0.4 m x 0.5 m face: 4260 Pa and 2130 Pa, wear 1e-9 and 5e-10 m/s (3.6, 1.8 µm/h).
  m.cells = {{Eigen::Vector2d(-0.2, 0.0), Eigen::Vector2d(0.2, 0.0), Eigen::Vector2d(0.2, -0.5)},
             {Eigen::Vector2d(-0.2, 0.0), Eigen::Vector2d(0.2, -0.5), Eigen::Vector2d(-0.2, -0.5)}};
  m.pressure = {4260.0, 2130.0};
  m.wear_rate = {1e-9, 5e-10};
  m.peak_pressure_y = -0.1;
  m.pressure_centre_y = -0.2;
  for (auto& p : r.predictions)
    if (p.model == "m1") p.prediction.maps.push_back(m);
  reports::ReportInput in;
  in.dataset = &d;
  in.baseline = &r;
  const std::string html = reports::report_html(in);
  const std::string md = reports::report_markdown(in);
  const auto plate = section(html, "<section id=\"plate\"", "</section>");
  BOOST_TEST(plate.find(">normal pressure (kPa)</text>") != std::string::npos, plate.substr(0, 3000));
  BOOST_TEST(plate.find(">4.26</text>") != std::string::npos);   // the bar's top
  BOOST_TEST(plate.find(">2.13</text>") != std::string::npos);   // and its middle
  BOOST_TEST(plate.find(">wear rate (µm/h)</text>") != std::string::npos);
  BOOST_TEST(plate.find(">3.60</text>") != std::string::npos);
  static const std::regex exponent(R"([0-9]e[-+][0-9])");
  BOOST_TEST(!std::regex_search(plate, exponent));
  for (const auto* text : {&html, &md}) {
    BOOST_TEST(text->find("um/h") == std::string::npos);
    BOOST_TEST(text->find("pressure (Pa)") == std::string::npos);
  }
  BOOST_TEST(md.find("peak pressure (kPa)") != std::string::npos);
  BOOST_TEST(md.find("| 4.26 |") != std::string::npos, section(md, "## Plate loading", "\n## "));
}

}  // namespace chutelab::test
