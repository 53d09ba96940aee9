// estimate's exports for designers: the streamline points in its JSON and in --points
// (CSV) are the same numbers; the drawing has mm ticks, dimensions, a scale bar of 1, 2 or 5 x 10^k
// mm and, for a troughed belt, the trough's section; the sweep chart's force axis starts at 0 and
// marks the plate and the range where the belt is overfilled.
#include <boost/test/unit_test.hpp>
#include <cmath>
#include <map>
#include <regex>
#include <sstream>

#include "../design/dxf_points.h"
#include "cli_runner.h"

using namespace chutelab::test;
namespace fs = std::filesystem;

namespace {
std::size_t count(const std::string& s, const std::string& what) {
  std::size_t n = 0;
  for (auto at = s.find(what); at != std::string::npos; at = s.find(what, at + 1)) ++n;
  return n;
}
}  // namespace

BOOST_AUTO_TEST_SUITE(estimate_exports)

BOOST_AUTO_TEST_CASE(points_in_json_and_csv_are_the_same_numbers) {
  const fs::path dir = fresh_dir("estimate-points");
  const auto r = run_chutelab("estimate --belt-speed 4 --mass-flow 35 --plate-distance 450 --format json --points '" +
                              (dir / "p.csv").string() + "' --svg '" + (dir / "d.svg").string() + "'");
  BOOST_REQUIRE_MESSAGE(r.exit_code == 0, r.err);
  const auto json = json_streamline_points(r.out);
  BOOST_REQUIRE_EQUAL(json.size(), 4u);
  std::map<std::string, Points> csv;
  std::istringstream in(read_file(dir / "p.csv"));
  std::string line;
  std::getline(in, line);
  BOOST_TEST(line == "condition,streamline,point,x_mm,y_mm");
  while (std::getline(in, line)) {
    std::vector<std::string> f;
    std::stringstream ls(line);
    for (std::string c; std::getline(ls, c, ',');) f.push_back(c);
    BOOST_REQUIRE_EQUAL(f.size(), 5u);
    BOOST_TEST(std::stoul(f[2]) == csv[dxf_layer_of(f[1])].size());
    csv[dxf_layer_of(f[1])].emplace_back(std::stod(f[3]), std::stod(f[4]));
  }
  for (const auto& [layer, pts] : json) {
    BOOST_TEST(pts.size() > 60u, layer);
    BOOST_TEST((csv[layer] == pts), layer << ": CSV and JSON points differ");
  }
  // Each streamline starts at the top of the pulley wrap (x = 0 for a level belt) and ends on the
  // plate at its impact point.
  const auto korzen = json.at("STREAMLINE_KORZEN_CENTROID");
  BOOST_TEST(korzen.front().first == 0.0);
  BOOST_TEST(korzen.back().first == 450.0, boost::test_tools::tolerance(1e-6));
  const std::string svg = read_file(dir / "d.svg");
  BOOST_TEST(count(svg, "class=\"dimension\"") == 4u);  // plate distance, plate top, plate height, pulley
  BOOST_TEST(count(svg, "class=\"tick x\"") >= 4u);
  BOOST_TEST(count(svg, "class=\"tick y\"") >= 3u);
  BOOST_TEST(svg.find(">450 mm<") != std::string::npos);
  std::smatch m;
  BOOST_REQUIRE(std::regex_search(svg, m, std::regex("class=\"scale-bar\">[\\s\\S]*?>([0-9.]+) mm</text>")));
  const double bar = std::stod(m[1]);
  const double mantissa = bar / std::pow(10.0, std::floor(std::log10(bar)));
  BOOST_TEST((mantissa == 1.0 || mantissa == 2.0 || mantissa == 5.0), "scale bar " << bar << " mm");
  // Between 2/25 and 1/5 of the drawing's frame (614 px wide): the largest 1-2-5 length under a fifth.
  BOOST_REQUIRE(std::regex_search(svg, m, std::regex("class=\"scale-bar\"><rect x=\"[0-9.]+\" y=\"[0-9.]+\" width=\"([0-9.]+)\"")));
  const double bar_px = std::stod(m[1]);
  BOOST_TEST(bar_px >= 0.08 * 614 - 0.1);
  BOOST_TEST(bar_px <= 0.2 * 614 + 0.1);
  BOOST_TEST(svg.find("trough-section") == std::string::npos);  // the bundled rig's belt is flat
  // A 1000 mm pulley: the bar grows with the drawing (the old one stayed 100 mm, ~20 px).
  const std::string setup = read_file(fs::path(CHUTELAB_SOURCE_DIR) / "datasets/grima2010/setup.toml");
  write_file(dir / "big.toml", std::regex_replace(setup, std::regex("pulley_diameter_mm = [0-9.]+"), "pulley_diameter_mm = 1000"));
  const auto big = run_chutelab("estimate --setup '" + (dir / "big.toml").string() +
                                "' --belt-speed 4 --mass-flow 35 --plate-distance 1200 --svg '" + (dir / "big.svg").string() + "'");
  BOOST_REQUIRE_MESSAGE(big.exit_code == 0, big.err);
  const std::string bsvg = read_file(dir / "big.svg");
  BOOST_REQUIRE(std::regex_search(bsvg, m, std::regex("class=\"scale-bar\">[\\s\\S]*?>([0-9.]+) mm</text>")));
  BOOST_TEST(std::stod(m[1]) >= 200.0, "scale bar " << m[1] << " mm on a 1000 mm pulley");
  BOOST_TEST(bsvg.find(">Ø 1000 mm<") != std::string::npos);
}

BOOST_AUTO_TEST_CASE(a_troughed_belt_is_drawn_with_its_section_and_the_sweep_marks_overfilling) {
  const fs::path dir = fresh_dir("estimate-trough");
  const std::string setup = read_file(fs::path(CHUTELAB_SOURCE_DIR) / "datasets/grima2010/setup.toml");
  write_file(dir / "setup.toml",
             std::regex_replace(setup, std::regex("\\[belt\\]\n"), "[belt]\ntrough_angle_deg = 35\ncentre_roll_mm = 120\n"));
  const auto r = run_chutelab("estimate --setup '" + (dir / "setup.toml").string() +
                              "' --belt-speed 4 --mass-flow 35 --plate-distance 450 --svg '" + (dir / "d.svg").string() + "'");
  BOOST_REQUIRE_MESSAGE(r.exit_code == 0, r.err);
  const std::string svg = read_file(dir / "d.svg");
  BOOST_TEST(svg.find("class=\"trough-section\"") != std::string::npos);
  BOOST_TEST(svg.find("class=\"load-section\"") != std::string::npos);
  BOOST_TEST(svg.find("class=\"trough-edge\"") != std::string::npos);
  // A capacity sweep past what the trough holds: the chart bands the overfilled points.
  const auto s = run_chutelab("estimate --setup '" + (dir / "setup.toml").string() +
                              "' --belt-speed 2 --plate-distance 450 --sweep mass_flow=20:400:20 --format csv --svg '" +
                              (dir / "s.svg").string() + "'");
  BOOST_REQUIRE_MESSAGE(s.exit_code == 0, s.err);
  BOOST_REQUIRE_MESSAGE(s.out.find("overfills") != std::string::npos, s.out);
  const std::string chart = read_file(dir / "s.svg");
  BOOST_TEST(chart.find("class=\"no-answer-label\" font-size=\"11\" fill=\"#a33\">belt overfilled<") != std::string::npos);
  BOOST_TEST(chart.find("class=\"plate-extent\"") != std::string::npos);
  // The force panel (the second x-scale) starts at 0 N; the impact panel does not have to.
  std::vector<double> y0;
  const std::regex scale("class=\"x-scale\"[^>]* data-y0=\"([-0-9.e]+)\"");
  for (auto it = std::sregex_iterator(chart.begin(), chart.end(), scale); it != std::sregex_iterator(); ++it)
    y0.push_back(std::stod((*it)[1]));
  BOOST_REQUIRE_EQUAL(y0.size(), 2u);
  BOOST_TEST(y0[1] == 0.0);
}

BOOST_AUTO_TEST_SUITE_END()
