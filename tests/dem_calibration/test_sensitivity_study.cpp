// The Table 6 study's bookkeeping on made-up outcomes: the variants, the change against the base and
// the verdict on the reference study's conclusion (both ways), and that the outputs carry the numbers.
#define BOOST_TEST_MODULE dem_sensitivity_study
#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>

#include "reports/sensitivity_page.h"
#include "studies/sensitivity.h"

using namespace chutelab::studies;
using chutelab::reports::sensitivity_html;
using chutelab::reports::sensitivity_md;

namespace {

// The quick base as resolved: 13.6 mm spheres at a third of the dataset's modulus.
Table6Base quick_base() {
  Table6Base b;
  b.diameter = 13.6e-3;
  b.modulus_scale = 1.0 / 3.0;
  return b;
}

const SensitivityVariant* find(const std::vector<SensitivityVariant>& v, const std::string& key) {
  for (const auto& x : v)
    if (x.key == key) return &x;
  return nullptr;
}

// Fluctuation of the 5.6 and 9 mm variants and the 13.6 mm base: 4 / fluct_mid / 8 N.
SensitivityStudy made_up(double lsd_force, double fluct_mid) {
  SensitivityStudy s;
  s.dataset = "x";
  s.dataset_name = "grima2010";
  s.condition = "V3-41";
  s.quality = "quick";
  s.belt_speed = 3;
  s.mass_flow = 41 / 3.6;
  s.base = quick_base();
  for (const auto& v : table6_variants(s.base)) {
    SensitivityRow r;
    r.variant = v;
    r.outcome.diameter = v.diameter;
    r.outcome.resultant = {100.0, 1.0};
    r.outcome.fluct_resultant = 20.0;
    r.outcome.collision_time = 2.5e-4;
    r.outcome.dt = 0.092 * 2.5e-4;  // the Rayleigh cap, not 0.1 t_c
    if (v.key == "LSD") r.outcome.resultant.value = lsd_force;
    if (v.key == "base") r.outcome.fluct_resultant = 8.0;
    if (v.key == "d=9mm") r.outcome.fluct_resultant = fluct_mid;
    if (v.key == "d=5.6mm") r.outcome.fluct_resultant = 4.0;
    s.rows.push_back(r);
  }
  evaluate(s);
  return s;
}

}  // namespace

// Variants around a 13.6 mm base: LSD, the reference study's two clumps (10.7 mm spheres, and spheres of the
// base's 13.6 mm), dt/20, G x10, G/10, and the reference study's absolute sizes other than the base, ascending.
BOOST_AUTO_TEST_CASE(table6_variants_around_the_base) {
  const auto v = table6_variants(quick_base());
  BOOST_TEST(v.size() == 9u);
  BOOST_TEST(v[0].key == "base");
  const auto* clump = find(v, "clump");
  BOOST_REQUIRE(clump);
  BOOST_TEST(clump->shape == "clump");
  BOOST_TEST(std::abs(clump->diameter - 13.6e-3 * 4.4 / 5.6) < 1e-12);
  const auto* clump_d = find(v, "clump-d");
  BOOST_REQUIRE(clump_d);
  BOOST_TEST(clump_d->shape == "clump");
  BOOST_TEST(clump_d->diameter == 13.6e-3);
  BOOST_TEST(find(v, "dt/20")->dt_fraction == 0.05);
  BOOST_TEST(find(v, "dt/20")->rayleigh_fraction == 0.1);
  BOOST_TEST(v[7].key == "d=5.6mm");
  BOOST_TEST(v[8].key == "d=9mm");
  BOOST_TEST(!find(v, "d=13.6mm"));  // the base itself
  // Labels say what runs: the quick base's modulus is a third of the dataset's; the step is capped.
  BOOST_TEST(v[0].label.find("the dataset's G / 3") != std::string::npos, v[0].label);
  BOOST_TEST(v[0].label.find("at most 0.2 t_R") != std::string::npos, v[0].label);
  BOOST_TEST(find(v, "Gx10")->label.find("the dataset's G x 3.33") != std::string::npos);
  Table6Base paper;  // at the reference study's base, 5.6 mm at the dataset's modulus: its own 9 and 13.6 mm
  paper.diameter = 5.6e-3;
  const auto p = table6_variants(paper);
  BOOST_TEST(p.size() == 9u);
  BOOST_TEST(p[7].key == "d=9mm");
  BOOST_TEST(p[8].key == "d=13.6mm");
  BOOST_TEST(p[0].label.find("the dataset's G") != std::string::npos);
  BOOST_TEST(p[0].label.find("G /") == std::string::npos);
  Table6Base odd = quick_base();  // --sizes in any order, repeats and the base dropped
  odd.sizes = {20e-3, 9e-3, 13.6e-3, 9e-3};
  const auto o = table6_variants(odd);
  BOOST_TEST(o.size() == 9u);
  BOOST_TEST(o[7].key == "d=9mm");
  BOOST_TEST(o[8].key == "d=20mm");
}

// Change = R/R_base - 1 with the standard errors combined; verdict reproduced when every
// contact/shape/dt/G variant is within 10 % and the fluctuation rises with every step up in d
// (5.6 -> 9 -> 13.6 mm, whatever the row order); not reproduced otherwise.
BOOST_AUTO_TEST_CASE(verdict_follows_the_numbers) {
  const SensitivityStudy ok = made_up(104.0, 6.0);
  BOOST_TEST(ok.rows[1].change.value == 4.0, boost::test_tools::tolerance(1e-9));
  BOOST_TEST(ok.rows[1].change.se == 104.0 * std::hypot(1.0 / 104.0, 1.0 / 100.0), boost::test_tools::tolerance(1e-9));
  BOOST_TEST(ok.verdict.reproduced());
  BOOST_TEST(ok.verdict.worst_variant == "LSD");
  BOOST_TEST(ok.verdict.size_fluctuation.front().first == 5.6e-3);
  BOOST_TEST(ok.verdict.size_fluctuation.back().first == 13.6e-3);
  BOOST_TEST(ok.verdict.text.find("REPRODUCED") != std::string::npos);
  const SensitivityStudy big = made_up(115.0, 6.0);
  BOOST_TEST(!big.verdict.mean_insensitive);
  BOOST_TEST(!big.verdict.reproduced());
  const SensitivityStudy flat = made_up(104.0, 9.0);  // 9 mm fluctuates more than the 13.6 mm base
  BOOST_TEST(!flat.verdict.fluctuation_grows);
  BOOST_TEST(flat.verdict.text.find("NOT reproduced") != std::string::npos);
  SensitivityStudy part = made_up(104.0, 6.0);  // only the base and LSD: not a verdict
  part.rows.resize(2);
  evaluate(part);
  BOOST_TEST(!part.verdict.reproduced());
  BOOST_TEST(part.verdict.text.find("NOT FULLY TESTED") != std::string::npos);
  const std::string csv = sensitivity_csv(ok), md = sensitivity_md(ok), html = sensitivity_html(ok);
  BOOST_TEST(std::count(csv.begin(), csv.end(), '\n') == 10);
  BOOST_TEST(md.find("| LSD |") != std::string::npos);
  BOOST_TEST(md.find("base 0.092 t\\_c (not 0.1)") != std::string::npos);  // the cap, said
  BOOST_TEST(html.find("base 0.092 t_c (not 0.1)") != std::string::npos);  // without Markdown's escapes
  BOOST_TEST(html.find("t\\_c") == std::string::npos);
  BOOST_TEST(md.find("`grima2010`") != std::string::npos);
  BOOST_TEST(html.find("<svg") != std::string::npos);
  BOOST_TEST(html.find("REPRODUCED") != std::string::npos);
  // The chart is also a file of its own, which the Markdown links (and the page does not show as text).
  const std::string svg = chutelab::reports::sensitivity_svg(ok);
  BOOST_TEST(svg.rfind("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<svg xmlns=\"http://www.w3.org/2000/svg\" ", 0) == 0);
  BOOST_TEST(svg.find("id=\"sensitivity-chart\"") != std::string::npos);
  BOOST_TEST(md.find("](sensitivity.svg)\n") != std::string::npos);
  BOOST_TEST(html.find("sensitivity.svg") == std::string::npos);
}

// A size of the reference study's Table 6 left out (5.6 mm at quick) is never silent: the verdict is
// "not fully tested" with the command that runs it, even when everything that ran agrees with the
// reference study.
BOOST_AUTO_TEST_CASE(a_left_out_size_is_not_fully_tested) {
  SensitivityStudy s = made_up(104.0, 6.0);
  s.rows.erase(std::remove_if(s.rows.begin(), s.rows.end(), [](const SensitivityRow& r) { return r.variant.key == "d=5.6mm"; }),
               s.rows.end());
  s.sizes_left_out = {5.6e-3};
  evaluate(s);
  BOOST_TEST(!s.verdict.reproduced());
  BOOST_TEST(s.verdict.fluctuation_grows);
  BOOST_TEST(s.verdict.text.find("NOT FULLY TESTED: 5.6 mm left out at quick quality (run with --sizes 5.6,9,13.6)") !=
                 std::string::npos,
             s.verdict.text);
  BOOST_TEST(s.verdict.text.find("on what ran it is reproduced") != std::string::npos);
  const auto f = sensitivity_finding(&s, "liggghts-rig");
  BOOST_TEST((f.status == chutelab::validation::FindingStatus::partly));
  BOOST_TEST(f.claims.at(1).undecided);
  BOOST_TEST(f.claims.at(0).evidence.find("grima2010 (not this dataset)") != std::string::npos, f.claims.at(0).evidence);
}

// What the CSV carries comes back: dataset name, quality, the left-out size, the base's modulus and
// step as resolved (so the labels read back say the same), and the verdict.
BOOST_AUTO_TEST_CASE(csv_round_trip_keeps_provenance_and_labels) {
  SensitivityStudy s = made_up(104.0, 6.0);
  s.rows.erase(std::remove_if(s.rows.begin(), s.rows.end(), [](const SensitivityRow& r) { return r.variant.key == "d=5.6mm"; }),
               s.rows.end());
  s.sizes_left_out = {5.6e-3};
  evaluate(s);
  const auto dir = std::filesystem::temp_directory_path() / "chutelab-sensitivity-roundtrip";
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "sensitivity.csv") << sensitivity_csv(s);
  const SensitivityStudy r = read_sensitivity_csv(dir / "sensitivity.csv");
  BOOST_TEST(r.dataset_name == "grima2010");
  BOOST_TEST(r.quality == "quick");
  BOOST_REQUIRE(r.sizes_left_out.size() == 1u);
  BOOST_TEST(r.sizes_left_out[0] == 5.6e-3, boost::test_tools::tolerance(1e-9));
  BOOST_TEST(r.base.modulus_scale == 1.0 / 3.0, boost::test_tools::tolerance(1e-5));
  BOOST_REQUIRE(r.rows.size() == s.rows.size());
  for (std::size_t k = 0; k < r.rows.size(); ++k) BOOST_TEST(r.rows[k].variant.label == s.rows[k].variant.label);
  BOOST_TEST(r.verdict.text == s.verdict.text);
}

BOOST_AUTO_TEST_CASE(finding_6_follows_the_sensitivity_verdict) {
  using chutelab::validation::FindingStatus;
  BOOST_TEST((sensitivity_finding(nullptr).status == FindingStatus::not_testable));
  SensitivityStudy s;
  s.condition = "V3-41";
  s.quality = "quick";
  auto& v = s.verdict;
  v.mean_tested = v.size_tested = true;
  v.mean_insensitive = true;
  v.fluctuation_grows = true;
  v.size_fluctuation = {{0.0136, 5.9}, {0.0219, 10.7}};
  BOOST_TEST((sensitivity_finding(&s).status == FindingStatus::reproduced));
  v.fluctuation_grows = false;
  BOOST_TEST((sensitivity_finding(&s).status == FindingStatus::partly));
  v.mean_insensitive = false;
  BOOST_TEST((sensitivity_finding(&s).status == FindingStatus::not_reproduced));
  v.size_tested = false;
  v.mean_tested = false;
  BOOST_TEST((sensitivity_finding(&s).status == FindingStatus::not_testable));
}
