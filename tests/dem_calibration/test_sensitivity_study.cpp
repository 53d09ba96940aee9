// The Table 6 study's bookkeeping on made-up outcomes: the variants, the change against the base and
// the verdict on the seed's conclusion (both ways), and that the outputs carry the numbers.
#define BOOST_TEST_MODULE dem_sensitivity_study
#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <cmath>

#include "reports/sensitivity_study.h"

using namespace chutelab::reports;

namespace {

SensitivityStudy made_up(double lsd_force, double fluct_mid) {
  SensitivityStudy s;
  s.dataset = "x";
  s.condition = "V3-41";
  s.quality = "quick";
  s.belt_speed = 3;
  s.mass_flow = 41 / 3.6;
  for (const auto& v : table6_variants(13.6e-3)) {
    SensitivityRow r;
    r.variant = v;
    r.outcome.diameter = v.diameter;
    r.outcome.resultant = {100.0, 1.0};
    r.outcome.fluct_resultant = 20.0;
    if (v.key == "LSD") r.outcome.resultant.value = lsd_force;
    // Fluctuations of the base (13.6 mm) and the 21.9 and 33 mm spheres.
    if (v.key == "base") r.outcome.fluct_resultant = 8.0;
    if (v.key == "d=21.9mm") r.outcome.fluct_resultant = fluct_mid;
    s.rows.push_back(r);
  }
  evaluate(s);
  return s;
}

}  // namespace

// Variants as in the seed's Table 6 around a 13.6 mm base: LSD, clump (10.7 mm spheres), dt/20, G x10,
// G/10, and the seed's scale-up factors 9/5.6 and 13.6/5.6 of the base: 21.9 and 33 mm.
BOOST_AUTO_TEST_CASE(table6_variants_around_the_base) {
  const auto v = table6_variants(13.6e-3);
  BOOST_TEST(v.size() == 8u);
  BOOST_TEST(v[0].key == "base");
  BOOST_TEST(v[2].shape == "clump");
  BOOST_TEST(std::abs(v[2].diameter - 13.6e-3 * 4.4 / 5.6) < 1e-12);
  BOOST_TEST(v[3].dt_fraction == 0.05);
  BOOST_TEST(v[6].key == "d=21.9mm");
  BOOST_TEST(v[7].key == "d=33mm");
  const auto paper = table6_variants(5.6e-3);  // at the seed's base: its own 9 and 13.6 mm
  BOOST_TEST(paper.size() == 8u);
  BOOST_TEST(paper[6].key == "d=9mm");
  BOOST_TEST(paper[7].key == "d=13.6mm");
}

// Change = R/R_base - 1 with the standard errors combined; verdict reproduced when every
// contact/shape/dt/G variant is within 10 % and the fluctuation rises with d; not reproduced otherwise.
BOOST_AUTO_TEST_CASE(verdict_follows_the_numbers) {
  const SensitivityStudy ok = made_up(104.0, 12.0);
  BOOST_TEST(ok.rows[1].change.value == 4.0, boost::test_tools::tolerance(1e-9));
  BOOST_TEST(ok.rows[1].change.se == 104.0 * std::hypot(1.0 / 104.0, 1.0 / 100.0), boost::test_tools::tolerance(1e-9));
  BOOST_TEST(ok.verdict.reproduced());
  BOOST_TEST(ok.verdict.worst_variant == "LSD");
  BOOST_TEST(ok.verdict.text.find("REPRODUCED") != std::string::npos);
  const SensitivityStudy big = made_up(115.0, 12.0);
  BOOST_TEST(!big.verdict.mean_insensitive);
  BOOST_TEST(!big.verdict.reproduced());
  const SensitivityStudy flat = made_up(104.0, 25.0);  // 21.9 mm fluctuates more than 33 mm
  BOOST_TEST(!flat.verdict.fluctuation_grows);
  BOOST_TEST(flat.verdict.text.find("NOT reproduced") != std::string::npos);
  SensitivityStudy part = made_up(104.0, 12.0);  // only the base and LSD: not a verdict
  part.rows.resize(2);
  evaluate(part);
  BOOST_TEST(!part.verdict.reproduced());
  BOOST_TEST(part.verdict.text.find("NOT FULLY TESTED") != std::string::npos);
  const std::string csv = sensitivity_csv(ok), md = sensitivity_md(ok), html = sensitivity_html(ok);
  BOOST_TEST(std::count(csv.begin(), csv.end(), '\n') == 9);
  BOOST_TEST(md.find("| LSD |") != std::string::npos);
  BOOST_TEST(html.find("<svg") != std::string::npos);
  BOOST_TEST(html.find("REPRODUCED") != std::string::npos);
}
