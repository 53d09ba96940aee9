// estimate --sweep and --svg as a designer uses them on the terminal.
#include <algorithm>
#include <boost/test/unit_test.hpp>
#include <cmath>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "cli_runner.h"

using namespace chutelab::test;

namespace {
std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> out;
  std::string cell;
  std::istringstream in(s);
  while (std::getline(in, cell, sep)) out.push_back(cell);
  if (!s.empty() && s.back() == sep && sep != '\n') out.emplace_back();  // a trailing empty cell
  return out;
}

// The number after "<key>," in estimate's (long) CSV; NaN when absent.
double csv_value(const std::string& csv, const std::string& key) {
  const auto at = csv.find("," + key + ",");
  return at == std::string::npos ? std::nan("") : std::stod(csv.substr(at + key.size() + 2));
}

int count(const std::string& s, const std::string& what) {
  int n = 0;
  for (auto at = s.find(what); at != std::string::npos; at = s.find(what, at + 1)) ++n;
  return n;
}
}  // namespace

BOOST_AUTO_TEST_SUITE(estimate_sweep)

BOOST_AUTO_TEST_CASE(each_sweep_row_is_the_single_estimate_at_that_value) {
  const auto s = run_chutelab("estimate --belt-speed 4 --mass-flow 35 --sweep plate_distance=300:600:100 --format csv");
  BOOST_TEST_REQUIRE(s.exit_code == 0, s.err);
  const auto lines = split(s.out, '\n');
  BOOST_TEST_REQUIRE(lines.size() == 5u);  // header + 300, 400, 500, 600
  const auto header = split(lines[0], ',');
  BOOST_TEST(header.front() == "plate_distance_mm");
  BOOST_TEST(header.back() == "note");
  for (const auto& h : header)  // units in every numeric column's name (flags and the note aside)
    if (h != "note" && h != "stationary_flow" && h != "discharge_high_speed" && h != "stream_thickness_from_continuity" &&
        h != "poisson_ratio" && h.find("ratio_K") == std::string::npos && !h.ends_with("_fraction"))
      BOOST_TEST((h.ends_with("_mm") || h.ends_with("_mps") || h.ends_with("_deg") || h.ends_with("_N") || h.ends_with("_Pa") || h.ends_with("_mm2") ||
                  h.ends_with("_s") || h.ends_with("_tph") || h.ends_with("_mm2")), "column without a unit: " << h);
  for (std::size_t row = 1; row < lines.size(); ++row) {
    const auto cells = split(lines[row], ',');
    BOOST_TEST_REQUIRE(cells.size() == header.size());
    const auto one = run_chutelab("estimate --belt-speed 4 --mass-flow 35 --plate-distance " + cells[0] + " --format csv");
    BOOST_TEST_REQUIRE(one.exit_code == 0);
    for (std::size_t c = 0; c < header.size(); ++c) {
      const auto& h = header[c];
      if (h.starts_with("korzen_") && h != "korzen_centroid_impact_y_mm" && !h.starts_with("korzen_centroid")) {
        const double single = csv_value(one.out, "korzen," + h.substr(7));
        if (cells[c].empty())  // not predicted at this point (V_a without stationary flow)
          BOOST_TEST(std::isnan(single), h << " at " << cells[0]);
        else
          BOOST_TEST(std::stod(cells[c]) == single, h << " at " << cells[0]);  // same code, same digits
      }
    }
  }
}

BOOST_AUTO_TEST_CASE(sweeps_over_rig_fields_and_effects_change_what_they_should) {
  const auto angle = run_chutelab("estimate --belt-speed 4 --mass-flow 35 --plate-distance 450 --sweep plate_angle=-10:10:10 --format csv");
  BOOST_TEST_REQUIRE(angle.exit_code == 0, angle.err);
  BOOST_TEST(angle.out.starts_with("plate_angle_deg,"));
  BOOST_TEST(count(angle.out, "\n") == 4);
  const auto drag = run_chutelab("estimate --belt-speed 4 --mass-flow 35 --plate-distance 450 --sweep air_drag=0:1:0.5 --format json");
  BOOST_TEST_REQUIRE(drag.exit_code == 0, drag.err);
  BOOST_TEST(drag.out.find("\"sweep\": {\"name\": \"air_drag\", \"from\": 0, \"to\": 1, \"step\": 0.5, \"points\": 3}") != std::string::npos);
  BOOST_TEST(count(drag.out, "\"estimate\": {") == 3);
  BOOST_TEST(drag.out.find("\"effects\": {\"air_drag\": 0.5}") != std::string::npos);
  // Drag slows the stream: V_p at C_d = 1 is below V_p without drag.
  const auto table = run_chutelab("estimate --belt-speed 4 --mass-flow 35 --plate-distance 450 --sweep air_drag=0:1:1");
  BOOST_TEST_REQUIRE(table.exit_code == 0);
  const auto rows = split(table.out, '\n');
  BOOST_TEST_REQUIRE(rows.size() >= 5u);
  std::istringstream r0(rows[3]), r1(rows[4]);
  double x0, v0, x1, v1;
  r0 >> x0 >> v0;
  r1 >> x1 >> v1;
  BOOST_TEST(x0 == 0.0);
  BOOST_TEST(x1 == 1.0);
  BOOST_TEST(v1 < v0);
}

BOOST_AUTO_TEST_CASE(points_without_an_answer_are_rows_with_a_note) {
  // At 1 m/s, 35 t/h no longer fits the flat belt: that row says so, the others answer.
  const auto s = run_chutelab("estimate --mass-flow 35 --plate-distance 400 --sweep belt_speed=1:3:1 --format csv");
  BOOST_TEST_REQUIRE(s.exit_code == 0, s.err);
  const auto lines = split(s.out, '\n');
  BOOST_TEST_REQUIRE(lines.size() == 4u);
  BOOST_TEST(lines[1].starts_with("1,,"));
  BOOST_TEST(lines[1].find("cross-section") != std::string::npos);
  BOOST_TEST(lines[2].find("cross-section") == std::string::npos);
}

// The stream's upper limit crosses the plate's top edge (y = 115 mm) between 4.80 and 4.85 m/s: the
// rows from there say how much passes over and what the plate takes (the share of Korzen's R_n), and
// the mean pressure (of the caught part over the band left on the plate) moves without a jump.
BOOST_AUTO_TEST_CASE(a_stream_partly_over_the_top_edge_is_noted_with_the_caught_force) {
  const auto dir = fresh_dir("estimate-overshoot");
  const auto s = run_chutelab("estimate --mass-flow 35 --plate-distance 450 --plate-top 115 "
                              "--sweep belt_speed=4.7:5.2:0.05 --format csv --svg '" + (dir / "sweep.svg").string() + "'");
  BOOST_TEST_REQUIRE(s.exit_code == 0, s.err);
  // The chart bands those points in both panels, one run each (4.85 to 5.2 m/s, from half a step
  // before the first), with what the plate takes there as the band's tooltip, and says what the band means.
  const std::string chart = read_file(dir / "sweep.svg");
  BOOST_TEST(count(chart, "class=\"overshoot-band\"") == 2, chart);
  BOOST_TEST(count(chart, ">part over the top edge</text>") == 2);
  BOOST_TEST(chart.find("<title>belt_speed_mps = 4.85: ") != std::string::npos);
  BOOST_TEST(chart.find("Banded in yellow: part of the stream passes over the plate&#39;s top edge") != std::string::npos);
  {
    std::smatch scale, band;
    BOOST_TEST_REQUIRE(std::regex_search(chart, scale, std::regex("class=\"x-scale\" data-d0=\"([^\"]+)\" data-d1=\"([^\"]+)\" "
                                                                  "data-r0=\"([^\"]+)\" data-r1=\"([^\"]+)\"")));
    BOOST_TEST_REQUIRE(std::regex_search(chart, band, std::regex("<rect x=\"([^\"]+)\" y=\"[^\"]+\" width=\"([^\"]+)\"[^>]*"
                                                                 "class=\"overshoot-band\"")));
    const double d0 = std::stod(scale[1]), d1 = std::stod(scale[2]), r0 = std::stod(scale[3]), r1 = std::stod(scale[4]);
    auto at = [&](double v) { return r0 + (v - d0) / (d1 - d0) * (r1 - r0); };
    // Drawn at 0.1 px: the band's left edge at 4.825 m/s and its right one at the frame's edge or 5.225 m/s.
    BOOST_TEST(std::stod(band[1]) == at(4.825), boost::test_tools::tolerance(0.1 / at(4.825)));
    BOOST_TEST(std::stod(band[1]) + std::stod(band[2]) == std::min(at(5.225), r1), boost::test_tools::tolerance(0.2 / r1));
  }
  const auto lines = split(s.out, '\n');
  const auto header = split(lines[0], ',');
  auto col = [&](const std::string& n) {
    return static_cast<std::size_t>(std::find(header.begin(), header.end(), n) - header.begin());
  };
  BOOST_TEST_REQUIRE(col("over_top_fraction") < header.size());
  double last_pressure = 0.0;
  int noted = 0;
  for (std::size_t row = 1; row < lines.size(); ++row) {
    // The note is the last cell, quoted: it holds commas.
    const auto note_at = lines[row].find(",\"");
    const std::string note = note_at == std::string::npos ? "" : lines[row].substr(note_at + 2);
    const auto cells = split(lines[row].substr(0, note_at), ',');
    const double speed = std::stod(cells[0]), over = std::stod(cells[col("over_top_fraction")]);
    const double caught = std::stod(cells[col("caught_normal_force_N")]), whole = std::stod(cells[col("normal_force_N")]);
    const double pressure = std::stod(cells[col("mean_pressure_Pa")]);
    BOOST_TEST_CONTEXT("belt speed " << speed) {
      BOOST_TEST((over > 0.0) == (speed > 4.81), over);
      if (over > 0.0) {
        ++noted;
        BOOST_TEST(note.find(" % of the stream passes over the plate's top edge: the plate takes R_n = ") != std::string::npos, note);
        BOOST_TEST(caught == (1.0 - over) * whole, boost::test_tools::tolerance(1e-12));
      } else {
        BOOST_TEST(note.empty(), note);
        BOOST_TEST(caught == whole);
      }
      // Steps of 0.05 m/s move the pressure by 2-4 % (the flow's momentum grows with V_b, and past
      // the crossing the band narrows faster than the caught force falls): no jump at the crossing.
      if (last_pressure > 0.0) BOOST_TEST(std::abs(pressure / last_pressure - 1.0) < 0.06);
    }
    last_pressure = pressure;
  }
  BOOST_TEST(noted >= 5);
}

BOOST_AUTO_TEST_CASE(bad_sweep_specs_exit_2_with_a_clear_message) {
  const std::string base = "estimate --belt-speed 4 --mass-flow 35 ";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"--sweep plate_distance=300:700", "NAME=FROM:TO:STEP"},
      {"--sweep plate_distance", "NAME=FROM:TO:STEP"},
      {"--sweep colour=1:2:1", "unknown input 'colour'"},
      {"--sweep plate_distance=300:700:-50", "never gets from 300 to 700"},
      {"--sweep plate_distance=300:700:0", "never gets from 300 to 700"},
      {"--sweep plate_distance=3e2mm:700:50", "FROM '3e2mm'"},
      {"--sweep plate_distance=300:nan:50", "TO 'nan'"},
      {"--sweep plate_distance=0:700:50", "must stay positive"},
      {"--sweep plate_distance=1:1e9:0.01", "at most"},
      {"--sweep plate_angle_deg=0:90:10 --plate-distance 400", "outside its physical range"},
      {"--sweep air_drag=0:9:1 --plate-distance 400", "outside its range"},
      {"--sweep belt_speed=1:3:1 --plate-distance 400", "leave out --belt-speed"},
      {"--plate-distance 400 --sweep air_drag=0:1:0.5 --effect air_drag=0.2", "leave out --effect air_drag"},
  };
  for (const auto& [args, message] : cases) {
    const auto r = run_chutelab(base + args);
    BOOST_TEST(r.exit_code == 2, args);
    BOOST_TEST(r.out.empty(), args);
    BOOST_TEST(r.err.find(message) != std::string::npos, args << " -> " << r.err);
  }
}

BOOST_AUTO_TEST_CASE(svg_draws_the_design_and_the_sweep_chart) {
  const auto dir = fresh_dir("estimate-svg");
  const auto one = run_chutelab("estimate --belt-speed 4 --mass-flow 35 --plate-distance 450 --svg '" +
                                (dir / "design.svg").string() + "'");
  BOOST_TEST_REQUIRE(one.exit_code == 0, one.err);
  const std::string svg = read_file(dir / "design.svg");
  BOOST_TEST(svg.starts_with("<?xml"));
  BOOST_TEST(svg.find("xmlns=\"http://www.w3.org/2000/svg\"") != std::string::npos);
  BOOST_TEST(count(svg, "class=\"streamline ") == 4);
  BOOST_TEST(count(svg, "class=\"plate\"") == 1);
  BOOST_TEST(count(svg, "class=\"impact-point ") == 2);
  BOOST_TEST(svg.find("R<tspan baseline-shift=\"sub\" font-size=\"75%\">n</tspan> = 38.89 N") != std::string::npos);
  const auto sweep = run_chutelab("estimate --mass-flow 35 --plate-distance 400 --sweep belt_speed=2:6:1 --svg '" +
                                  (dir / "sweep.svg").string() + "' --format csv");
  BOOST_TEST_REQUIRE(sweep.exit_code == 0, sweep.err);
  const std::string chart = read_file(dir / "sweep.svg");
  BOOST_TEST(chart.find("class=\"plot sweep-chart\"") != std::string::npos);
  BOOST_TEST(count(chart, "class=\"series\"") == 7);  // four impact lines, three forces
  BOOST_TEST(count(chart, "overshoot") == 0);          // the plate takes the whole stream throughout
  // An input is never overwritten, and a failed run leaves no file behind.
  const std::string setup = std::string(CHUTELAB_SOURCE_DIR) + "/datasets/grima2010/setup.toml";
  const auto over = run_chutelab("estimate --setup '" + setup + "' --belt-speed 4 --mass-flow 35 --plate-distance 450 --svg '" + setup + "'");
  BOOST_TEST(over.exit_code == 2);
  BOOST_TEST(over.err.find("is an input of this run") != std::string::npos, over.err);
  const auto bad = run_chutelab("estimate --belt-speed -4 --mass-flow 35 --plate-distance 450 --svg '" +
                                (dir / "never.svg").string() + "'");
  BOOST_TEST(bad.exit_code == 2);
  BOOST_TEST(!std::filesystem::exists(dir / "never.svg"));
}

BOOST_AUTO_TEST_SUITE_END()
