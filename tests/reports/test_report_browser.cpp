#define BOOST_TEST_MODULE report_browser
// report.html in a real browser (headless Chromium): it loads without errors, fetches nothing,
// every picture has a size and content, no label sticks out of its picture, and the expected
// sections and plots are there. A script injected into a copy of the page does the checking and
// writes its verdict into the DOM, which Chromium dumps.
// Our own main: without a browser nothing here can be checked, and ctest must show that as a skip
// (SKIP_RETURN_CODE in CMakeLists.txt), not as a pass.
#define BOOST_TEST_NO_MAIN
#include <boost/test/unit_test.hpp>
#include <chrono>
#include <cstdlib>
#include <fmt/format.h>
#include <fstream>
#include <iostream>
#include <set>
#include <sstream>
#include <unistd.h>

#include "effects/registry.h"
#include "reports/report.h"
#include "validation/diagnosis.h"
#include "validation/strength_fit.h"
#include "validation/harness.h"
#include "validation/synthesize.h"
#include "validation/tolerances.h"

namespace chutelab::test {
namespace {
namespace fs = std::filesystem;

const fs::path kChromium = "/usr/bin/chromium";

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

void spit(const fs::path& p, const std::string& text) {
  fs::create_directories(p.parent_path());
  std::ofstream(p, std::ios::binary) << text;
}

fs::path work_dir(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / fmt::format("chutelab-report-browser-{}", ::getpid()) / name;
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

// Records errors from the very start of the page (script errors and failed resource loads).
constexpr std::string_view kRecorder = R"(<script>
window.__errors = [];
window.onerror = function (msg, src, line) { window.__errors.push('script error: ' + msg + ' at ' + line); };
window.addEventListener('error', function (e) {
  if (e.target && e.target !== window) window.__errors.push('resource failed: ' + (e.target.src || e.target.href || e.target.tagName));
}, true);
</script>
)";

// Runs after the page has loaded; `EXPECT` is replaced by the test's expectations.
constexpr std::string_view kChecker = R"(<script>
(function () {
  var expect = EXPECT;
  function check() {
    var bad = window.__errors.slice();
    var svgs = document.querySelectorAll('svg');
    if (svgs.length === 0) bad.push('no svg at all');
    for (var i = 0; i < svgs.length; ++i) {
      var s = svgs[i], r = s.getBoundingClientRect();
      if (!(r.width > 0 && r.height > 0)) bad.push('svg with an empty box: ' + s.id);
      var b = s.getBBox();
      if (!(b.width > 0 && b.height > 0)) bad.push('svg with nothing drawn: ' + s.id);
      var texts = s.querySelectorAll('text');
      for (var k = 0; k < texts.length; ++k) {
        var t = texts[k].getBoundingClientRect();
        if (t.width > 0 && (t.left < r.left - 1 || t.right > r.right + 1 || t.top < r.top - 1 || t.bottom > r.bottom + 1))
          bad.push('text outside its picture: "' + texts[k].textContent + '" in ' + s.id);
      }
      if (s.classList.contains('plot') && !s.classList.contains('traj-legend')) {
        if (!s.querySelector('.plot-title')) bad.push('plot without a title: ' + s.id);
        if (!s.querySelector('.axis-label')) bad.push('plot without axis labels: ' + s.id);
        if (!s.classList.contains('trajectory-panel') && !s.querySelector('.legend')) bad.push('plot without a legend: ' + s.id);
      }
    }
    expect.sections.forEach(function (id) {
      if (!document.getElementById(id)) bad.push('missing element #' + id);
    });
    Object.keys(expect.counts).forEach(function (sel) {
      var n = document.querySelectorAll(sel).length;
      if (n !== expect.counts[sel]) bad.push(sel + ': ' + n + ' found, ' + expect.counts[sel] + ' expected');
    });
    Object.keys(expect.at_least).forEach(function (sel) {
      var n = document.querySelectorAll(sel).length;
      if (n < expect.at_least[sel]) bad.push(sel + ': ' + n + ' found, at least ' + expect.at_least[sel] + ' expected');
    });
    // Before/after pairs: two columns, side by side (same top, the second right of the first) or,
    // on a narrow window, stacked; never wider than the window.
    function columns(id) {
      var el = document.getElementById(id);
      if (!el) { bad.push('missing pair #' + id); return null; }
      var cols = el.querySelectorAll(':scope > .ba-col');
      if (cols.length !== 2) { bad.push('#' + id + ': ' + cols.length + ' columns'); return null; }
      return [cols[0].getBoundingClientRect(), cols[1].getBoundingClientRect()];
    }
    expect.side_by_side.forEach(function (id) {
      var c = columns(id);
      if (c && !(Math.abs(c[0].top - c[1].top) < 1 && c[1].left >= c[0].right - 1))
        bad.push('#' + id + ' not side by side');
    });
    expect.stacked.forEach(function (id) {
      var c = columns(id);
      if (c && !(c[1].top >= c[0].bottom - 1)) bad.push('#' + id + ' not stacked');
    });
    // The story's order: each selector's first element after the previous one's.
    var prev = null;
    expect.order.forEach(function (sel) {
      var el = document.querySelector(sel);
      if (!el) { bad.push('order: nothing matches ' + sel); return; }
      if (prev && !(prev.el.compareDocumentPosition(el) & Node.DOCUMENT_POSITION_FOLLOWING))
        bad.push('order: ' + sel + ' comes before ' + prev.sel);
      prev = {el: el, sel: sel};
    });
    // The first chart under the verdict, its title and first row of panels on the first screen.
    var measured = '';
    if (expect.first_screen) {
      var verdict = document.querySelector('.verdict'), chart = document.querySelector('svg.plot');
      if (!verdict || !chart) bad.push('first screen: no verdict or no chart');
      else {
        var vr = verdict.getBoundingClientRect(), cr = chart.getBoundingClientRect();
        measured = ' [first chart #' + chart.id + ' at ' + Math.round(cr.top) + '-' + Math.round(cr.bottom) +
                   ' px, verdict ends at ' + Math.round(vr.bottom) + ' px, window ' + window.innerHeight + ' px]';
        if (cr.top < vr.bottom - 1) bad.push('first screen: the first chart is above the verdict');
        if (cr.top + Math.min(cr.height, expect.first_screen) > window.innerHeight)
          bad.push('first screen: the first chart starts at ' + Math.round(cr.top) + ' px, so its first ' +
                   expect.first_screen + ' px are not on a ' + window.innerHeight + ' px screen');
      }
    }
    // Folded sections opened, no table is wider than its box (no horizontal scroll inside the page).
    if (expect.tables_fit) {
      document.querySelectorAll('details').forEach(function (d) { d.open = true; });
      document.querySelectorAll('.table-wrap').forEach(function (w) {
        if (w.scrollWidth > w.clientWidth + 1) {
          var t = w.querySelector('table');
          bad.push('table wider than its box: #' + (t && t.id ? t.id : '?') + ' ' + w.scrollWidth + ' > ' + w.clientWidth + ' px');
        }
      });
    }
    if (document.documentElement.scrollWidth > window.innerWidth + 1)
      bad.push('page wider than the window: ' + document.documentElement.scrollWidth + ' > ' + window.innerWidth);
    var fetched = performance.getEntriesByType('resource');
    for (var j = 0; j < fetched.length; ++j) bad.push('page fetched ' + fetched[j].name);
    var out = document.createElement('pre');
    out.id = 'chutelab-check';
    out.textContent = (bad.length ? 'FAIL: ' + bad.join(' | ') : 'PASS') + ' [svgs=' + svgs.length + ']' + measured;
    document.body.appendChild(out);
  }
  if (document.readyState === 'complete') check(); else window.addEventListener('load', check);
})();
</script>
)";

struct Expectations {
  std::vector<std::string> ids;
  std::vector<std::pair<std::string, int>> counts, at_least;
  std::vector<std::string> side_by_side, stacked;  // ids of before/after pairs
  std::vector<std::string> order;                   // CSS selectors in document order
  int first_screen = 0;      // > 0: the first chart starts under the verdict with this much of it on screen
  bool tables_fit = false;   // no table wider than its box, folded sections opened
  std::string js() const {
    auto quote = [](const std::string& s) { return "'" + s + "'"; };
    std::string o = "{sections: [";
    for (const auto& id : ids) o += quote(id) + ",";
    o += "], counts: {";
    for (const auto& [sel, n] : counts) o += fmt::format("{}: {},", quote(sel), n);
    o += "}, at_least: {";
    for (const auto& [sel, n] : at_least) o += fmt::format("{}: {},", quote(sel), n);
    o += "}, side_by_side: [";
    for (const auto& id : side_by_side) o += quote(id) + ",";
    o += "], stacked: [";
    for (const auto& id : stacked) o += quote(id) + ",";
    o += "], order: [";
    for (const auto& sel : order) o += quote(sel) + ",";
    return o + fmt::format("], first_screen: {}, tables_fit: {}}}", first_screen, tables_fit ? "true" : "false");
  }
};

// The browser's verdict on a page, or the reason it could not be obtained.
std::string browse(const fs::path& dir, const std::string& html, const Expectations& e, int window_width = 1200) {
  std::string page = html;
  const auto head = page.find("<head>");
  const auto body_end = page.rfind("</body>");
  BOOST_REQUIRE(head != std::string::npos && body_end != std::string::npos);
  std::string checker(kChecker);
  checker.replace(checker.find("EXPECT"), 6, e.js());
  page.insert(body_end, checker);
  page.insert(head + 6, kRecorder);
  spit(dir / "check.html", page);
  const fs::path profile = dir / "profile";  // fresh: no state from earlier runs or other users
  fs::remove_all(profile);
  const std::string cmd = fmt::format(
      "timeout 90 '{}' --headless --no-sandbox --disable-gpu --disable-quic --no-first-run "
      "--disable-background-networking --disable-component-update --disable-sync --disable-extensions "
      "--user-data-dir='{}' --window-size={},900 --virtual-time-budget=5000 --dump-dom 'file://{}' "
      ">'{}' 2>'{}' </dev/null",
      kChromium.string(), profile.string(), window_width, fs::absolute(dir / "check.html").string(),
      (dir / "dom.html").string(),
      (dir / "stderr.txt").string());
  const int status = std::system(cmd.c_str());
  const std::string dom = slurp(dir / "dom.html");
  const auto at = dom.find("id=\"chutelab-check\">");
  if (at == std::string::npos)
    return fmt::format("no verdict in the DOM (chromium exit status {}); stderr: {}", status,
                       slurp(dir / "stderr.txt").substr(0, 2000));
  const auto start = at + std::string("id=\"chutelab-check\">").size();
  return dom.substr(start, dom.find("</pre>", start) - start);
}

int quantities_with_normalised_error(const validation::ValidationResult& r) {
  std::set<std::string> q;
  for (const auto& c : r.comparisons)
    if (c.normalised_error()) q.insert(c.quantity);
  return static_cast<int>(q.size());
}

void finish(const fs::path& dir, const std::string& verdict, double seconds) {
  BOOST_TEST_MESSAGE("browser verdict: " << verdict << " (" << seconds << " s); page: " << (dir / "report.html"));
  BOOST_TEST(verdict.starts_with("PASS"), verdict);
  if (verdict.starts_with("PASS") && !std::getenv("CHUTELAB_KEEP_REPORTS")) fs::remove_all(dir);
}

double since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

// The bundled virtual-experiment rig, models as they are, with tolerances that some values break.
BOOST_AUTO_TEST_CASE(reference_rig_report_renders_in_chromium) {
  const auto t0 = std::chrono::steady_clock::now();
  const fs::path dir = work_dir("reference");
  const auto d = validation::read_dataset(fs::path(CHUTELAB_SOURCE_DIR) / "datasets" / "liggghts-rig");
  spit(dir / "tolerances.toml",
       "[korzen]\nshear_force_N = { relative = 0.5 }\nresultant_force_N = { relative = 0.03 }\n"
       "[\"*\"]\nimpact_point_y_mm = { absolute = 5.0 }\n");
  const auto tol = validation::Tolerances::read(dir / "tolerances.toml");
  validation::ValidateOptions opt;
  opt.tolerances = &tol;
  const auto r = validation::validate(d, validation::make_models({"korzen", "booth-cema"}), opt);
  BOOST_REQUIRE(r.acceptance_failed);

  reports::ReportInput in;
  in.dataset = &d;
  in.baseline = &r;
  in.notes = {"Tolerances chosen by the test so that some values fail."};
  const std::string html = reports::report_html(in);
  spit(dir / "report.html", html);
  spit(dir / "report.md", reports::report_markdown(in));

  const int n = static_cast<int>(d.stations.size());
  Expectations e;
  e.ids = {"summary", "forces", "velocities", "trajectories", "residuals", "failures", "failures-table",
           "table4-base", "table5-base", "bars-base", "traj-base", "resid-base", "trends-base", "vv20"};
  e.counts = {{"#traj-base .trajectory-panel", n},
              {"#resid-base .residual-panel", quantities_with_normalised_error(r)},
              {"#table4-base tbody tr", n},
              {"#table5-base tbody tr", n},
              {"#bars-base rect.bar", 2 * n},  // measured and korzen (booth-cema predicts no R)
              {"#missing", 0}};
  e.at_least = {{"#table4-base td.fail", 1}, {"#table5-base td.fail", 1}, {"#traj-base polyline", 4 * n},
                {"#failures-table tbody tr", r.failed_count()}, {"#table5-base td.beyond", 1}};
  // The story first: verdict, where the models fail, what failed acceptance, then the detail.
  e.order = {"h1", ".verdict", "#resid-base", "#failures", "#summary", "#forces", "#velocities", "#trajectories",
             "#trends", "#vv20"};
  e.first_screen = 250;
  e.tables_fit = true;
  const std::string verdict = browse(dir, html, e, 1400);
  finish(dir, verdict, since(t0));
}

// A synthetic dataset with hidden air drag: diagnosis, the fitted effect, before and after.
BOOST_AUTO_TEST_CASE(diagnosis_and_before_after_report_renders_in_chromium) {
  const auto t0 = std::chrono::steady_clock::now();
  const fs::path dir = work_dir("synthetic");
  const auto rig = validation::read_dataset(fs::path(CHUTELAB_SOURCE_DIR) / "datasets" / "grima2010",
                                            validation::MeasurementsRequired::no);
  const auto* drag = effects::find("air_drag");
  BOOST_REQUIRE(drag);
  validation::SynthesizeOptions so;
  so.effects = {drag->make(0.6)};
  so.seed = 5;
  validation::write_outputs(dir / "data", validation::synthesize(rig, validation::make_models({"korzen", "booth-cema"}), so), {},
                            "synthesize");
  const auto d = validation::read_dataset(dir / "data");

  const auto models = validation::make_models({"korzen", "booth-cema"});
  const auto g = validation::diagnose(d, validation::make_models({"booth-cema", "korzen"}));
  const auto* best = g.best();
  BOOST_REQUIRE(best);
  BOOST_REQUIRE(best->effects.size() == 1u);
  const auto* info = effects::find(best->effects.front());
  BOOST_REQUIRE(info);

  const auto before = validation::validate(d, models);
  validation::ValidateOptions opt;
  opt.effects = {info->make(best->estimate.front())};
  opt.effect_labels = {fmt::format("{}={:.4g} (fitted)", info->name, best->estimate.front())};
  const auto after = validation::validate(d, models, opt);

  reports::ReportInput in;
  in.dataset = &d;
  in.baseline = &before;
  in.with_effects = &after;
  in.diagnosis = &g;
  in.effects.push_back({info->name, info->parameter, info->unit, info->physics, info->source,
                        best->estimate.front(), best->uncertainty.front(), true});
  const std::string html = reports::report_html(in);
  spit(dir / "report.html", html);
  spit(dir / "report.md", reports::report_markdown(in));

  const int n = static_cast<int>(d.stations.size());
  Expectations e;
  e.ids = {"summary", "missing", "before-after", "ranking-chart", "rms-before-after", "forces", "velocities",
           "trajectories", "residuals", "table4-base", "table4-effects", "table5-effects", "bars-effects",
           "resid-base", "resid-effects-pair", "trends-effects", "vv20-table", "vv20-table-effects"};
  e.counts = {{"#traj-base .trajectory-panel", n},
              {"#traj-effects .trajectory-panel", n},
              {"#resid-base .residual-panel", quantities_with_normalised_error(before)},
              {"#resid-effects-pair .residual-panel", quantities_with_normalised_error(after)},
              {"#ranking-chart rect.bar", static_cast<int>(g.singles.size() + g.pairs.size())},
              {"#rms-before-after rect.bar", 4},
              {"#trends-pair .residual-chart", 2},
              {"#before-after #resid-change .residual-change-panel", quantities_with_normalised_error(before)},
              {"#failures", 0}};
  e.at_least = {{"#residuals li", 1}, {"#ranking tbody tr", 1}};
  // Verdict, where the models fail, the effect's before and after, the diagnosis, then the detail.
  e.order = {"h1", ".verdict", "#resid-base", "#before-after", "#resid-change", "#missing", "#summary", "#forces",
             "#trends", "#vv20"};
  e.first_screen = 250;
  e.tables_fit = true;
  const std::vector<std::string> pairs = {"summary-pair", "forces-pair", "velocities-pair", "trajectories-pair",
                                          "trends-pair"};
  // At 1400 px the pairs lie side by side, except Table 5's, whose many columns do not fit half the
  // window: it stacks instead of scrolling.
  e.side_by_side = {"summary-pair", "forces-pair", "trajectories-pair", "trends-pair"};
  e.stacked = {"velocities-pair"};
  const std::string verdict = browse(dir, html, e, 1400);
  // A narrow window: the same page, every pair one column under the other.
  Expectations narrow = e;
  narrow.side_by_side.clear();
  narrow.stacked = pairs;
  narrow.first_screen = 0;
  const std::string narrow_verdict = browse(dir / "narrow", html, narrow, 900);
  BOOST_TEST(narrow_verdict.starts_with("PASS"), "900 px window: " << narrow_verdict);
  finish(dir, verdict, since(t0));
}

// The checker is not vacuous: a page with a script error, an empty picture, a label outside its
// picture and a missing section fails, naming each problem.
BOOST_AUTO_TEST_CASE(checker_catches_a_broken_page) {
  const fs::path dir = work_dir("broken");
  const std::string html =
      "<!DOCTYPE html><html><head><meta charset=\"utf-8\"></head><body>"
      "<svg id=\"empty\" width=\"0\" height=\"0\"></svg>"
      "<svg id=\"spill\" class=\"plot\" width=\"100\" height=\"50\" viewBox=\"0 0 100 50\">"
      "<rect width=\"10\" height=\"10\"/><text x=\"90\" y=\"20\">far too long a label</text></svg>"
      "<p class=\"verdict\">the verdict, below its chart</p>"
      "<div class=\"table-wrap\" style=\"width: 100px; overflow-x: auto\"><table id=\"wide\" style=\"width: 500px\">"
      "<tr><td>x</td></tr></table></div>"
      "<div class=\"before-after\" id=\"pair\"><div class=\"ba-col\">a</div><div class=\"ba-col\">b</div></div>"
      "<div style=\"width: 3000px\">wide</div>"
      "<script>undefined_function();</script></body></html>\n";
  Expectations e;
  e.ids = {"summary"};
  e.side_by_side = {"pair"};
  e.order = {"#pair", "#spill"};
  e.first_screen = 10;
  e.tables_fit = true;
  const std::string verdict = browse(dir, html, e);
  BOOST_TEST_MESSAGE("verdict on the broken page: " << verdict);
  BOOST_TEST(verdict.starts_with("FAIL"), verdict);
  for (const char* problem : {"script error", "svg with an empty box: empty", "text outside its picture",
                              "missing element #summary", "plot without a title: spill", "#pair not side by side",
                              "page wider than the window", "order: #spill comes before #pair",
                              "first screen: the first chart is above the verdict",
                              "table wider than its box: #wide"})
    BOOST_TEST(verdict.find(problem) != std::string::npos, problem);
  fs::remove_all(dir);
}

}  // namespace chutelab::test

int main(int argc, char* argv[]) {
  using chutelab::test::kChromium;
  if (!std::filesystem::exists(kChromium)) {
    std::cerr << "SKIPPED: " << kChromium << " is not installed (scripts/setup.sh installs Debian's chromium); "
                 "the report was not checked in a browser.\n";
    return CHUTELAB_SKIP_RETURN_CODE;
  }
  return boost::unit_test::unit_test_main(&init_unit_test, argc, argv);
}
