#define BOOST_TEST_MODULE design_page
// The designer's page (`chutelab design`) in headless Chromium, opened from file:// as a designer
// would: the inputs are set through the page's URL hash, the page computes with its WebAssembly
// build of estimate, and every number it shows must equal what `chutelab estimate --format json`
// prints for the design the page exports (its conditions.csv line and setup.toml, read back by the
// strict dataset reader). A screenshot of the page is kept in the build tree for people to look at.
// Our own main: without Chromium or without emscripten at build time nothing here can be checked,
// and ctest shows that as skipped (SKIP_RETURN_CODE), not passed.
#define BOOST_TEST_NO_MAIN
#include <boost/test/unit_test.hpp>
#include <cmath>
#include <cstdlib>
#include <fmt/format.h>
#include <fstream>
#include <iostream>
#include <map>
#include <optional>
#include <regex>
#include <sstream>

#include "../cli/cli_runner.h"

namespace chutelab::test {
namespace {
namespace fs = std::filesystem;
// A relative tolerance for BOOST_TEST.
inline auto tt_tolerance(double t) { return boost::test_tools::tolerance(t); }

const fs::path kChromium = "/usr/bin/chromium";

std::string html_unescape(std::string s) {
  for (auto [from, to] : {std::pair{"&lt;", "<"}, {"&gt;", ">"}, {"&quot;", "\""}, {"&#39;", "'"}, {"&amp;", "&"}}) {
    for (auto at = s.find(from); at != std::string::npos; at = s.find(from, at + 1)) s.replace(at, std::string(from).size(), to);
  }
  return s;
}

std::string chromium(const fs::path& dir, const std::string& url, const std::string& mode) {
  const fs::path profile = dir / "profile";
  fs::remove_all(profile);
  const std::string cmd = fmt::format(
      "timeout 120 '{}' --headless --no-sandbox --disable-gpu --disable-quic --no-first-run "
      "--disable-background-networking --disable-component-update --disable-sync --disable-extensions "
      "--hide-scrollbars --user-data-dir='{}' --window-size=1400,1900 --virtual-time-budget=60000 {} '{}' "
      ">'{}' 2>'{}' </dev/null",
      kChromium.string(), profile.string(), mode, url, (dir / "stdout.txt").string(), (dir / "stderr.txt").string());
  const int status = std::system(cmd.c_str());
  BOOST_TEST_MESSAGE("chromium " << mode << " exit status " << status);
  return read_file(dir / "stdout.txt");
}

struct PageView {
  std::string dom, state;
  std::map<std::string, std::string> values;  // output id -> data-value
  std::map<std::string, std::string> shown;   // output id -> text shown
  std::string conditions_csv, setup_toml, error;
  std::map<std::string, std::string> marks;  // input id -> the page's words under that field
  std::string stream_note, chart_note;
};

PageView open_page(const fs::path& dir, const fs::path& page, const std::string& hash) {
  PageView v;
  // A second try only when the browser gave up before the module was even loaded (a machine so
  // busy that the page's heartbeat did not cover the compile); a page in any other state is judged.
  for (int attempt = 0; attempt < 2; ++attempt) {
    v.dom = chromium(dir, "file://" + fs::absolute(page).string() + "#" + hash, "--dump-dom");
    if (v.dom.find("<body data-state=\"loading\"") == std::string::npos) break;
    BOOST_TEST_MESSAGE("page still loading when the browser stopped; trying once more");
  }
  std::smatch m;
  if (std::regex_search(v.dom, m, std::regex("<body data-state=\"([a-z]+)\""))) v.state = m[1];
  const std::regex out("<output id=\"([A-Za-z_-]+)\"(?: class=\"[a-z]*\")? data-value=\"([^\"]*)\">([^<]*)</output>");
  for (auto it = std::sregex_iterator(v.dom.begin(), v.dom.end(), out); it != std::sregex_iterator(); ++it) {
    v.values[(*it)[1]] = (*it)[2];
    v.shown[(*it)[1]] = html_unescape((*it)[3]);
  }
  auto textarea = [&](const std::string& id) {
    std::smatch t;
    return std::regex_search(v.dom, t, std::regex("<textarea id=\"" + id + "\"[^>]*>([^<]*)</textarea>"))
               ? html_unescape(t[1]) : std::string();
  };
  v.conditions_csv = textarea("export-conditions");
  v.setup_toml = textarea("export-setup");
  if (std::regex_search(v.dom, m, std::regex("<div id=\"error\"[^>]*>([^<]*)</div>"))) v.error = html_unescape(m[1]);
  const std::regex mark("<div id=\"([^\"]+)-error\" class=\"field-error\"[^>]*>([^<]*)</div>");
  for (auto it = std::sregex_iterator(v.dom.begin(), v.dom.end(), mark); it != std::sregex_iterator(); ++it)
    v.marks[(*it)[1]] = html_unescape((*it)[2]);
  if (std::regex_search(v.dom, m, std::regex("<div id=\"stream-note\"[^>]*>([^<]*)</div>"))) v.stream_note = html_unescape(m[1]);
  if (std::regex_search(v.dom, m, std::regex("<p class=\"note\" id=\"chart-note\">([^<]*)</p>"))) v.chart_note = html_unescape(m[1]);
  return v;
}

// A number from estimate's JSON: the value after "key": inside the object that `scope` opens.
std::optional<double> json_number(const std::string& json, const std::string& scope, const std::string& key) {
  auto at = scope.empty() ? std::size_t{0} : json.find("\"" + scope + "\": {");
  if (at == std::string::npos) return std::nullopt;
  const auto end = scope.empty() ? json.size() : json.find('}', at);
  const auto k = json.find("\"" + key + "\": ", at);
  if (k == std::string::npos || k > end) return std::nullopt;
  return std::stod(json.substr(k + key.size() + 4));
}

fs::path build_page(const std::string& name, const std::string& design_args = "") {
  const fs::path dir = fresh_dir("design-" + name);
  const auto r = run_chutelab("design --out '" + (dir / "page").string() + "' " + design_args);
  BOOST_TEST_REQUIRE(r.exit_code == 0, r.err);
  BOOST_TEST_REQUIRE(fs::exists(dir / "page" / "design.html"));
  return dir;
}

// The page against the CLI for one design given as a URL hash; `effects` are the matching flags.
PageView check_design(const std::string& name, const std::string& hash, const std::string& effects,
                      const std::string& design_args = "") {
  const fs::path dir = build_page(name, design_args);
  const fs::path page = dir / "page" / "design.html";
  const PageView v = open_page(dir, page, hash);
  BOOST_TEST_REQUIRE(v.state == "ready", "page state '" << v.state << "', error: " << v.error << "; stderr: "
                                                        << read_file(dir / "stderr.txt").substr(0, 1500));
  // The exported row is a dataset the strict reader takes; estimate on it is the reference.
  write_file(dir / "exported" / "conditions.csv", v.conditions_csv);
  write_file(dir / "exported" / "setup.toml", v.setup_toml);
  const auto cli = run_chutelab("estimate --dataset '" + (dir / "exported").string() + "' --condition " + name + " " +
                                effects + " --format json");
  BOOST_TEST_REQUIRE(cli.exit_code == 0, cli.err << "\nexported setup:\n" << v.setup_toml << "\nconditions:\n" << v.conditions_csv);
  const std::vector<std::tuple<std::string, std::string, std::string, int>> checks = {
      // output id, JSON scope, JSON key, decimals shown
      {"out-impact_velocity_mps", "korzen", "impact_velocity_mps", 3},
      {"out-impact_angle_deg", "", "impact_angle_deg", 2},
      {"out-exit_velocity_mps", "korzen", "exit_velocity_mps", 3},
      {"out-normal_force_N", "korzen", "normal_force_N", 2},
      {"out-shear_force_N", "korzen", "shear_force_N", 2},
      {"out-resultant_force_N", "korzen", "resultant_force_N", 2},
      {"out-impact_point_y_mm", "korzen", "impact_point_y_mm", 1},
      {"out-cema_impact_point_y_mm", "booth-cema", "impact_point_y_mm", 1},
      {"out-stream_thickness_mm", "condition", "stream_thickness_mm", 1},
      {"out-impact_zone_top_mm", "impact_zone", "impact_zone_top_mm", 1},
      {"out-impact_zone_bottom_mm", "impact_zone", "impact_zone_bottom_mm", 1},
      {"out-caught_normal_force_N", "impact_zone", "caught_normal_force_N", 2},
      {"out-caught_shear_force_N", "impact_zone", "caught_shear_force_N", 2},
      {"out-mean_pressure_Pa", "impact_zone", "mean_pressure_Pa", 0}};
  int compared = 0;
  for (const auto& [id, scope, key, decimals] : checks) {
    const auto expected = json_number(cli.out, scope, key);
    BOOST_TEST_REQUIRE(v.values.count(id), "no output " << id);
    if (!expected) {  // e.g. no V_a without stationary flow: the page must show none either
      BOOST_TEST(v.values.at(id).empty(), id << " shows " << v.values.at(id) << " where estimate has none");
      continue;
    }
    BOOST_TEST_REQUIRE(!v.values.at(id).empty(), id << " is empty; estimate says " << *expected);
    const double shown = std::stod(v.values.at(id));
    // Both print the same C++ computation at round-trip precision; the browser's libm (musl, in
    // the WebAssembly build) may round a sine or arctangent one ulp away from glibc's, which moves
    // the last digits only.
    BOOST_TEST(std::abs(shown - *expected) <= 2e-9 * std::max(1.0, std::abs(*expected)),
               id << ": page " << v.values.at(id) << ", estimate " << *expected);
    BOOST_TEST(v.shown.at(id) == fmt::format("{:.{}f}", *expected, decimals), id << " text " << v.shown.at(id));
    ++compared;
  }
  BOOST_TEST(compared >= 8);
  const bool stationary = cli.out.find("\"stationary_flow\": true") != std::string::npos;
  BOOST_TEST(v.values.at("verdict") == (stationary ? "true" : "false"));
  BOOST_TEST(v.shown.at("verdict") == (stationary ? "yes" : "no"));
  // The drawing and the chart are chutelab's own SVGs, and the chart marks the current design.
  BOOST_TEST(v.dom.find("class=\"design-picture\"") != std::string::npos);
  // The analytical impact zone is drawn on the plate face, where the DEM draws its pressure map.
  BOOST_TEST(v.dom.find("class=\"impact-zone\"") != std::string::npos);
  BOOST_TEST(v.dom.find("class=\"plot sweep-chart\"") != std::string::npos);
  BOOST_TEST(v.dom.find("class=\"current-design\"") != std::string::npos);
  std::size_t lines = 0;
  for (auto at = v.dom.find("class=\"streamline "); at != std::string::npos; at = v.dom.find("class=\"streamline ", at + 1)) ++lines;
  BOOST_TEST(lines == 4u);
  BOOST_TEST_MESSAGE(name << ": " << compared << " numbers equal estimate --format json; verdict "
                          << (stationary ? "stationary" : "no stationary flow"));
  return v;
}

}  // namespace

BOOST_AUTO_TEST_CASE(bundled_rig_at_4_mps_numbers_equal_estimate_json) {
  check_design("T1", "belt_speed=4&mass_flow=35&plate_distance=450&name=T1", "");
}

BOOST_AUTO_TEST_CASE(changed_rig_with_effects_numbers_equal_estimate_json_and_screenshot) {
  const std::string hash =
      "belt_speed=1.6&mass_flow=22&plate_distance=320&plate_top=160&plate.angle_deg=10&"
      "belt.pulley_diameter_mm=320&material.friction_plate=0.35&effect.air_drag=0.6&effect.plate_rebound=0.2&name=T2";
  check_design("T2", hash, "--effect air_drag=0.6 --effect plate_rebound=0.2");
  // The picture people look at: the page as it opens with this design.
  const fs::path dir = build_page("shot");
  const fs::path shot = fs::path(CHUTELAB_DESIGN_SCREENSHOT);
  fs::create_directories(shot.parent_path());
  fs::remove(shot);
  chromium(dir, "file://" + fs::absolute(dir / "page" / "design.html").string() + "#" + hash,
           "--screenshot='" + shot.string() + "'");
  BOOST_TEST_REQUIRE(fs::exists(shot));
  BOOST_TEST(fs::file_size(shot) > 50000u, "screenshot of " << fs::file_size(shot) << " bytes");
  BOOST_TEST_MESSAGE("screenshot: " << shot);
}

BOOST_AUTO_TEST_CASE(a_page_started_from_a_dataset_row_shows_that_rows_estimate) {
  // The LIGGGHTS rig's V3-41 has a measured h_b of its own; the page opens on that row.
  const std::string rig = std::string(CHUTELAB_SOURCE_DIR) + "/datasets/liggghts-rig";
  const PageView v = check_design("V3-41", "", "", "--dataset '" + rig + "' --condition V3-41");
  const auto row = run_chutelab("estimate --dataset '" + rig + "' --condition V3-41 --format json");
  BOOST_TEST_REQUIRE(row.exit_code == 0);
  for (const auto& [id, key] : {std::pair{"out-normal_force_N", "normal_force_N"}, {"out-impact_point_y_mm", "impact_point_y_mm"}})
    BOOST_TEST(std::abs(std::stod(v.values.at(id)) - *json_number(row.out, "korzen", key)) <= 2e-9 * 100, id);
  BOOST_TEST(std::stod(v.values.at("out-stream_thickness_mm")) == 34.0);
}

// The page speaks to designers: inputs labelled in words with units, no measurement effects (the
// registry's stage, not a list in the page), the design written back into the address as a link
// that reopens it, and an address key the page does not know said rather than dropped.
BOOST_AUTO_TEST_CASE(labels_effects_link_and_unknown_address_keys) {
  const fs::path dir = build_page("link");
  const PageView v = open_page(dir, dir / "page" / "design.html",
                               "belt_speed=3.5&mass_flow=30&plate_distance=400&belt.pulley_diameter_mm=400&"
                               "effect.air_drag=0.5&bogus_key=1&effect.load_cell_gain=1.02&name=L1");
  BOOST_TEST_REQUIRE(v.state == "ready", v.error);
  BOOST_TEST(v.dom.find("head pulley diameter (mm)") != std::string::npos);
  BOOST_TEST(v.dom.find(">belt.pulley_diameter_mm<") == std::string::npos);  // the key is a tooltip, not the label
  BOOST_TEST(v.dom.find("id=\"fx-air_drag\"") != std::string::npos);
  BOOST_TEST(v.dom.find("id=\"fx-load_cell_gain\"") == std::string::npos);
  BOOST_TEST(v.dom.find("id=\"fx-load_cell_offset\"") == std::string::npos);
  std::smatch m;
  BOOST_REQUIRE(std::regex_search(v.dom, m, std::regex("<div id=\"warning\"[^>]*>([^<]*)</div>")));
  const std::string warning = html_unescape(m[1]);
  BOOST_TEST(warning.find("\"bogus_key\"") != std::string::npos, warning);
  BOOST_TEST(warning.find("Measurement effects are not part of a design, ignored: effect.load_cell_gain") != std::string::npos,
             warning);
  BOOST_REQUIRE(std::regex_search(v.dom, m, std::regex("<a id=\"share-link\" href=\"([^\"]*)\"")));
  const std::string link = html_unescape(m[1]);
  for (const char* part : {"#belt_speed=3.5&", "&mass_flow=30&", "&plate_distance=400&", "&belt.pulley_diameter_mm=400&",
                           "&effect.air_drag=0.5&", "&name=L1"})
    BOOST_TEST(link.find(part) != std::string::npos, part << " not in " << link);
  BOOST_TEST(link.find("bogus") == std::string::npos);
  // The link reopens the same design: the same numbers on a fresh page.
  const fs::path again = build_page("link-again");
  const PageView w = open_page(again, again / "page" / "design.html", link.substr(1));
  BOOST_TEST_REQUIRE(w.state == "ready", w.error);
  for (const char* id : {"out-normal_force_N", "out-impact_point_y_mm", "out-stream_thickness_mm"})
    BOOST_TEST(w.values.at(id) == v.values.at(id), id);
}

// The readout's numbers against `estimate --format json` for the design given as flags.
void expect_readout_of(const PageView& v, const std::string& flags) {
  const auto cli = run_chutelab("estimate " + flags + " --format json");
  BOOST_TEST_REQUIRE(cli.exit_code == 0, cli.err);
  for (const auto& [id, scope, key] : {std::tuple{"out-normal_force_N", "korzen", "normal_force_N"},
                                       {"out-impact_point_y_mm", "korzen", "impact_point_y_mm"},
                                       {"out-stream_thickness_mm", "condition", "stream_thickness_mm"},
                                       {"out-mean_pressure_Pa", "impact_zone", "mean_pressure_Pa"}}) {
    BOOST_TEST_REQUIRE(v.values.count(id), "no output " << id);
    BOOST_TEST_REQUIRE(!v.values.at(id).empty(), id << " is empty");
    const double expected = *json_number(cli.out, scope, key);
    BOOST_TEST(std::abs(std::stod(v.values.at(id)) - expected) <= 2e-9 * std::max(1.0, std::abs(expected)),
               id << ": page " << v.values.at(id) << ", estimate " << flags << ": " << expected);
  }
}

// The drawing, the chart and the exports are all there (of the design shown).
void expect_whole_page(const PageView& v) {
  BOOST_TEST(v.dom.find("class=\"design-picture\"") != std::string::npos);
  BOOST_TEST(v.dom.find("class=\"plot sweep-chart\"") != std::string::npos);
  BOOST_TEST(v.conditions_csv.find("condition,belt_speed_mps") == 0u, v.conditions_csv);
  BOOST_TEST(v.setup_toml.find("[belt]") != std::string::npos);
  BOOST_TEST(v.dom.find("id=\"download-dxf\" download=") != std::string::npos);
  BOOST_TEST(v.dom.find("href=\"blob:") != std::string::npos);
}

// A bad entry in the address does not blank the page: the refused input is marked with chutelab's
// reason in the page's words (the field's label, not a flag), and the drawing, readout and exports
// are those of the design with the page's starting value for that input.
BOOST_AUTO_TEST_CASE(bad_input_keeps_a_drawing_and_marks_the_field) {
  const fs::path dir = build_page("bad");
  const fs::path page = dir / "page" / "design.html";
  const PageView neg = open_page(dir, page, "belt_speed=-1&mass_flow=35&plate_distance=450");
  BOOST_TEST(neg.state == "invalid", neg.state << ": " << neg.error);
  BOOST_TEST(neg.error.find("belt speed V_b (m/s): belt speed must be positive, got -1") != std::string::npos, neg.error);
  BOOST_TEST(neg.error.find("--belt-speed") == std::string::npos, neg.error);
  BOOST_TEST_REQUIRE(neg.marks.count("in-belt_speed"));
  BOOST_TEST(neg.marks.at("in-belt_speed") == "belt speed must be positive, got -1");
  expect_whole_page(neg);
  expect_readout_of(neg, "--belt-speed 4 --mass-flow 35 --plate-distance 450");
  BOOST_TEST(neg.conditions_csv.find("\ndesign-1,4,35,450,250,") != std::string::npos, neg.conditions_csv);

  // Text that is no number, as a hand-edited link carries it.
  const PageView abc = open_page(dir, page, "belt_speed=abc&mass_flow=30&plate_distance=450");
  BOOST_TEST(abc.state == "invalid", abc.state << ": " << abc.error);
  BOOST_TEST_REQUIRE(abc.marks.count("in-belt_speed"), abc.error);
  BOOST_TEST(abc.marks.at("in-belt_speed") == "\"abc\" is not a number");
  expect_whole_page(abc);
  expect_readout_of(abc, "--belt-speed 4 --mass-flow 30 --plate-distance 450");

  // An overfilled belt: the capacity is refused with the belt's own bound.
  const PageView full = open_page(dir, page, "belt_speed=4&mass_flow=5000&plate_distance=450");
  BOOST_TEST(full.state == "invalid", full.state << ": " << full.error);
  BOOST_TEST_REQUIRE(full.marks.count("in-mass_flow"), full.error);
  BOOST_TEST(full.marks.at("in-mass_flow").find("5000.0 t/h at 4.00 m/s needs") == 0u, full.marks.at("in-mass_flow"));
  BOOST_TEST(full.error.find("capacity m_s (t/h): 5000.0 t/h") == 0u, full.error);
  expect_whole_page(full);
  expect_readout_of(full, "--belt-speed 4 --mass-flow 35 --plate-distance 450");
}

// A page driven as a user would: `script` runs in the page once it shows its first design (a copy of
// the page with the script at its end), and the page is read when the script says it is done.
PageView drive_page(const std::string& name, const std::string& hash, const std::string& script) {
  const fs::path dir = build_page(name);
  std::string html = read_file(dir / "page" / "design.html");
  const auto end = html.rfind("</body>");
  BOOST_TEST_REQUIRE(end != std::string::npos);
  html.insert(end, "<script>(function () {\n"
                   "  function when(test, then) { (function poll() { if (test()) then(); else setTimeout(poll, 20); })(); }\n"
                   "  function state() { return document.body.getAttribute('data-state'); }\n"
                   "  function type(id, text) { var i = document.getElementById(id); i.value = text;\n"
                   "    i.dispatchEvent(new Event('input')); }\n" +
                       script + "\n})();</script>\n");
  write_file(dir / "driven.html", html);
  return open_page(dir, dir / "driven.html", hash);
}

// A change chutelab refuses after a valid design keeps that design: a slower belt overfills it, so
// the capacity is marked with the belt's bound and the belt speed the user moved with "not taken";
// the drawing, readout and exports stay those of the design before the change.
BOOST_AUTO_TEST_CASE(an_edit_chutelab_refuses_keeps_the_last_valid_design) {
  const PageView v = drive_page("edit", "belt_speed=4&mass_flow=35&plate_distance=450&name=E1",
                                "when(function () { return state() === 'ready'; }, function () {\n"
                                "  type('in-belt_speed', '0.3');\n"
                                "  when(function () { return state() !== 'ready'; }, function () {});\n"
                                "});");
  BOOST_TEST_REQUIRE(v.state == "invalid", v.state << ": " << v.error);
  BOOST_TEST_REQUIRE(v.marks.count("in-mass_flow"), v.error);
  BOOST_TEST(v.marks.at("in-mass_flow").find("35.0 t/h at 0.30 m/s") == 0u, v.marks.at("in-mass_flow"));
  BOOST_TEST_REQUIRE(v.marks.count("in-belt_speed"), v.error);
  BOOST_TEST(v.marks.at("in-belt_speed").find("not taken: capacity m_s (t/h): 35.0 t/h at 0.30 m/s") == 0u,
             v.marks.at("in-belt_speed"));
  BOOST_TEST(v.error.find("with belt speed V_b (m/s) = 0.3, capacity m_s (t/h): ") == 0u, v.error);
  BOOST_TEST(v.error.find("the last design chutelab could compute") != std::string::npos, v.error);
  expect_whole_page(v);
  expect_readout_of(v, "--belt-speed 4 --mass-flow 35 --plate-distance 450");
  BOOST_TEST(v.conditions_csv.find("\nE1,4,35,450,250,") != std::string::npos, v.conditions_csv);
  BOOST_TEST(v.dom.find("id=\"share-link\" href=\"#belt_speed=4&amp;") != std::string::npos);
}

// The sliders span the design's own bounds: the capacity slider ends at what the belt carries at
// this belt speed (estimate's limits, the bound continuity checks), not at a number in the page.
BOOST_AUTO_TEST_CASE(sliders_span_the_designs_limits) {
  const fs::path dir = build_page("sliders");
  const PageView v = open_page(dir, dir / "page" / "design.html", "belt_speed=4&mass_flow=35&plate_distance=450");
  BOOST_TEST_REQUIRE(v.state == "ready", v.error);
  const auto cli = run_chutelab("estimate --belt-speed 4 --mass-flow 35 --plate-distance 450 --format json");
  BOOST_TEST_REQUIRE(cli.exit_code == 0);
  auto slider_top = [&](const std::string& id) {
    std::smatch m;
    BOOST_TEST_REQUIRE(std::regex_search(v.dom, m, std::regex("id=\"" + id + "-slider\"[^>]*data-hi=\"([^\"]+)\"")), id);
    return std::stod(m[1]);
  };
  const double capacity = *json_number(cli.out, "limits", "mass_flow_tph_max");
  const double reach = *json_number(cli.out, "limits", "plate_distance_mm_max");
  // The browser's libm may round a sine one ulp from glibc's (see check_design); the reach is a
  // bisection to 0.1 mm that such an ulp cannot move unless it sits on a step.
  BOOST_TEST(slider_top("in-mass_flow") == capacity, tt_tolerance(1e-9));
  BOOST_TEST(slider_top("in-plate_distance") == reach, tt_tolerance(1e-9));
  BOOST_TEST(slider_top("in-belt_speed") == 50.0);  // validation's bound on any conveyor
  BOOST_TEST(capacity < 300.0);                     // this belt carries less than the page's old fixed end
  // The range follows the design: at 2.5 times the belt speed the belt carries 2.5 times as much.
  const fs::path fast = build_page("sliders-fast");
  const PageView w = open_page(fast, fast / "page" / "design.html", "belt_speed=10&mass_flow=35&plate_distance=450");
  BOOST_TEST_REQUIRE(w.state == "ready", w.error);
  std::smatch m;
  BOOST_TEST_REQUIRE(std::regex_search(w.dom, m, std::regex("id=\"in-mass_flow-slider\"[^>]*data-hi=\"([^\"]+)\"")));
  BOOST_TEST(std::stod(m[1]) == 2.5 * capacity, tt_tolerance(1e-9));
}

// A stream partly over the plate's top edge: the page says how much passes over and what the plate
// takes (the numbers of estimate's JSON), and the chart bands the points where it happens.
BOOST_AUTO_TEST_CASE(a_partial_overshoot_shows_its_note_and_band) {
  const PageView v = check_design("O1", "belt_speed=4.85&mass_flow=35&plate_distance=450&plate_top=108&sweep=belt_speed&name=O1", "");
  BOOST_TEST(v.stream_note.find("Partial overshoot: ") == 0u, v.stream_note);
  BOOST_TEST(v.stream_note.find("% of the stream passes over the plate's top edge: the plate takes R_n = ") != std::string::npos,
             v.stream_note);
  const double over = std::stod(v.values.at("out-over_top_percent"));
  BOOST_TEST(over > 0.5);
  BOOST_TEST(over < 50.0);
  BOOST_TEST(std::stod(v.values.at("out-caught_normal_force_N")) < std::stod(v.values.at("out-normal_force_N")));
  BOOST_TEST(v.dom.find("class=\"overshoot-band\"") != std::string::npos);
  BOOST_TEST(v.chart_note.find("Banded in yellow: part of the stream passes over the plate's top edge") == 0u, v.chart_note);
  // The same page with the plate's top well above the stream: no note, no band.
  const PageView whole = check_design("O2", "belt_speed=4.85&mass_flow=35&plate_distance=450&plate_top=250&sweep=belt_speed&name=O2", "");
  BOOST_TEST(whole.stream_note.empty(), whole.stream_note);
  BOOST_TEST(std::stod(whole.values.at("out-over_top_percent")) == 0.0);
  BOOST_TEST(whole.dom.find("class=\"overshoot-band\"") == std::string::npos);
  BOOST_TEST(whole.chart_note.empty(), whole.chart_note);
}

// The export goes through chutelab's one CSV writer (a name with a comma is quoted, one a
// spreadsheet would run as a formula gets its apostrophe) and reads back; a malformed %-escape in
// the address is said and skipped, the page stays whole and computes the rest.
BOOST_AUTO_TEST_CASE(export_uses_the_csv_writer_and_a_bad_address_is_said_not_blank) {
  const fs::path dir = build_page("csv");
  const PageView v = open_page(dir, dir / "page" / "design.html",
                               "belt_speed=4&mass_flow=35&plate_top=%E0%A4%A&plate_distance=450&name=%3DSUM(1%2C2)");
  BOOST_TEST_REQUIRE(v.state == "ready", v.error);
  BOOST_TEST(v.error.find("malformed %-escape") != std::string::npos, v.error);
  BOOST_TEST(v.conditions_csv.find("\n\"'=SUM(1,2)\",4,35,450,") != std::string::npos, v.conditions_csv);
  write_file(dir / "exported" / "conditions.csv", v.conditions_csv);
  write_file(dir / "exported" / "setup.toml", v.setup_toml);
  const auto cli = run_chutelab("estimate --dataset '" + (dir / "exported").string() + "' --condition '=SUM(1,2)'");
  BOOST_TEST(cli.exit_code == 0, cli.err);
}

BOOST_AUTO_TEST_CASE(design_checks_its_starting_rig_and_writes_nothing_on_bad_input) {
  const fs::path dir = fresh_dir("design-cli");
  write_file(dir / "bad.toml", "name = \"x\"\n[belt]\npulley_diameter_mm = -5\n");
  const auto bad = run_chutelab("design --setup '" + (dir / "bad.toml").string() + "' --out '" + (dir / "out").string() + "'");
  BOOST_TEST(bad.exit_code == 2);
  BOOST_TEST(bad.err.find("bad.toml") != std::string::npos, bad.err);
  BOOST_TEST(!fs::exists(dir / "out" / "design.html"));
  const auto other = run_chutelab("design --dataset '" + std::string(CHUTELAB_SOURCE_DIR) + "/datasets/liggghts-rig' --out '" +
                                  (dir / "rig").string() + "'");
  BOOST_TEST_REQUIRE(other.exit_code == 0, other.err);
  // The page starts from that rig: its setup.toml travels inside the page.
  BOOST_TEST(read_file(dir / "rig" / "design.html").find("liggghts-rig") != std::string::npos);
}

}  // namespace chutelab::test

int main(int argc, char* argv[]) {
  using chutelab::test::kChromium;
  if (!CHUTELAB_DESIGN_PAGE_BUILT) {
    std::cerr << "SKIPPED: this build has no designer's page (em++ from Debian's emscripten was not found or could "
                 "not build; scripts/setup.sh installs it).\n";
    return CHUTELAB_SKIP_RETURN_CODE;
  }
  if (!std::filesystem::exists(kChromium)) {
    std::cerr << "SKIPPED: " << kChromium << " is not installed (scripts/setup.sh installs Debian's chromium); "
                 "the designer's page was not checked in a browser.\n";
    return CHUTELAB_SKIP_RETURN_CODE;
  }
  return boost::unit_test::unit_test_main(&init_unit_test, argc, argv);
}
