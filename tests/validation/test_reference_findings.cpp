// The reference study's findings are decided from numbers: a hand-built result that has each pattern gives
// "reproduced", and breaking one pattern flips exactly the claim that depends on it.
#include <boost/test/unit_test.hpp>
#include <map>

#include "validation/reference_findings.h"

using namespace chutelab;
using namespace chutelab::validation;

namespace {

// Four conditions: 2 and 5 m/s, each at a low and a high flow.
struct Case {
  Dataset d;
  ValidationResult r;
  // (condition, model) -> values; measured per condition
  std::map<std::pair<std::string, std::string>, QuantityValues> pred;
  std::map<std::string, QuantityValues> meas;
  std::map<std::string, double> impact_u;  // measured impact point uncertainty, m (default 0.2 %)

  Case() {
    d.setup.material.friction_plate = 0.27;
    d.setup.belt.pulley_diameter = 0.25;
    d.setup.belt.loaded_width = 0.2;
    d.setup.material.bulk_density = 558;
    for (auto [c, v, m] : {std::tuple{"A", 2.0, 26.0}, {"B", 2.0, 41.0}, {"C", 5.0, 28.0}, {"D", 5.0, 44.0}})
      d.stations.push_back(make_station(d.setup, c, v, m / 3.6, 0.3, 0.25, 0.03));
    r.models = {"booth-cema", "korzen", "dem"};
    // A pattern with every finding: DEM R error 10 % at 2 m/s, 1 % at 5 m/s; ratios vary in DEM and
    // measurement; DEM V_p low, more at high flow; V_a matches; DEM impact point below Booth/CEMA,
    // Korzen's further off than Booth/CEMA's.
    const std::map<std::string, double> meas_R{{"A", 15}, {"B", 24}, {"C", 30}, {"D", 60}};
    const std::map<std::string, double> ratio{{"A", 0.16}, {"B", 0.15}, {"C", 0.07}, {"D", 0.06}};
    const std::map<std::string, double> dem_R_err{{"A", 0.10}, {"B", 0.08}, {"C", 0.01}, {"D", 0.002}};
    const std::map<std::string, double> dem_vp_err{{"A", -0.1}, {"B", -0.2}, {"C", -0.05}, {"D", -0.3}};
    for (const auto& st : d.stations) {
      const auto& c = st.condition;
      const bool fast = st.belt_speed >= 4;
      auto& m = meas[c];
      const double R = meas_R.at(c), rs = ratio.at(c);
      m[Quantity::normal_force] = R / std::hypot(1.0, rs);
      m[Quantity::shear_force] = *m[Quantity::normal_force] * rs;
      m[Quantity::resultant_force] = R;
      m[Quantity::impact_velocity] = st.belt_speed + 1.0;
      m[Quantity::exit_velocity] = 1.8;
      m[Quantity::impact_point_y] = 0.050;
      auto& k = pred[{c, "korzen"}];
      // R within 2 u_val of the measurement at the top condition (u = 0.2 % below)
      k[Quantity::normal_force] = R * 1.001 / std::hypot(1.0, 0.27);
      k[Quantity::shear_force] = *k[Quantity::normal_force] * 0.27;
      k[Quantity::resultant_force] = R * 1.001;
      if (!fast) k[Quantity::exit_velocity] = 1.2;
      k[Quantity::impact_point_y] = 0.060;
      auto& b = pred[{c, "booth-cema"}];
      b[Quantity::impact_point_y] = 0.055;
      auto& dm = pred[{c, "dem"}];
      const double Rd = R * (1 + dem_R_err.at(c));
      dm[Quantity::normal_force] = Rd / std::hypot(1.0, rs * 1.05);
      dm[Quantity::shear_force] = *dm[Quantity::normal_force] * rs * 1.05;
      dm[Quantity::resultant_force] = Rd;
      dm[Quantity::impact_velocity] = *m[Quantity::impact_velocity] + dem_vp_err.at(c);
      dm[Quantity::exit_velocity] = 1.805;
      dm[Quantity::impact_point_y] = 0.052;
    }
  }

  std::vector<ReferenceFinding> check() {
    r.predictions.clear();
    d.measurements.clear();
    for (const auto& [key, v] : pred) {
      ConditionResult cr{key.first, key.second, {}};
      cr.prediction.values = v;
      for (auto q : kAllQuantities)
        if (v[q] && key.second == "dem") cr.prediction.uncertainty[q] = 0.002 * std::abs(*v[q]);
      r.predictions.push_back(cr);
    }
    for (const auto& [c, v] : meas)
      for (auto q : kAllQuantities)
        if (v[q])
          d.measurements.push_back({c, q, *v[q],
                                    q == Quantity::impact_point_y && impact_u.count(c) ? impact_u.at(c)
                                                                                       : 0.002 * std::abs(*v[q]),
                                    {}});
    return check_reference_findings(d, r);
  }
};

const FindingClaim& claim(const std::vector<ReferenceFinding>& f, int finding, std::size_t k) {
  return f.at(static_cast<std::size_t>(finding - 1)).claims.at(k);
}

}  // namespace

BOOST_AUTO_TEST_CASE(every_pattern_present_gives_reproduced) {
  Case c;
  const auto f = c.check();
  BOOST_REQUIRE_EQUAL(f.size(), 5u);
  for (const auto& x : f) {
    BOOST_TEST_CONTEXT("finding " << x.number) {
      for (const auto& cl : x.claims) BOOST_TEST_MESSAGE(cl.text << ": " << cl.evidence);
      BOOST_TEST((x.status == FindingStatus::reproduced));
    }
  }
}

BOOST_AUTO_TEST_CASE(breaking_one_pattern_flips_its_claim) {
  {
    Case c;  // Korzen with stationary flow at 5 m/s
    c.pred[{"D", "korzen"}][Quantity::exit_velocity] = 1.0;
    const auto f = c.check();
    BOOST_TEST(!claim(f, 1, 0).holds);
    BOOST_TEST(claim(f, 1, 1).holds);
    BOOST_TEST((f[0].status == FindingStatus::partly));
  }
  {
    Case c;  // the DEM's ratio constant: both DEM force components share one ratio
    for (const char* k : {"A", "B", "C", "D"}) {
      auto& v = c.pred[{k, "dem"}];
      v[Quantity::shear_force] = *v[Quantity::normal_force] * 0.1;
    }
    const auto f = c.check();
    BOOST_TEST(!claim(f, 2, 1).holds);
    BOOST_TEST(claim(f, 2, 2).holds);
  }
  {
    Case c;  // DEM error growing with speed
    c.pred[{"A", "dem"}][Quantity::resultant_force] = 15.1;
    c.pred[{"B", "dem"}][Quantity::resultant_force] = 24.1;
    c.pred[{"C", "dem"}][Quantity::resultant_force] = 33.0;
    c.pred[{"D", "dem"}][Quantity::resultant_force] = 66.0;
    const auto f = c.check();
    BOOST_TEST(!claim(f, 3, 0).holds);
    BOOST_TEST(!claim(f, 3, 1).holds);
    BOOST_TEST(!claim(f, 3, 2).holds);  // 10 % off at the top condition
    BOOST_TEST((f[2].status == FindingStatus::not_reproduced));
  }
  {
    Case c;  // DEM V_p above the measurement at one condition, and less negative at high flow there
    *c.pred[{"B", "dem"}][Quantity::impact_velocity] += 0.5;
    const auto f = c.check();
    BOOST_TEST(!claim(f, 4, 0).holds);
    BOOST_TEST(!claim(f, 4, 1).holds);
    BOOST_TEST(claim(f, 4, 2).holds);
  }
  {
    Case c;  // the DEM above Booth/CEMA at one condition; Korzen closer than Booth/CEMA
    c.pred[{"C", "dem"}][Quantity::impact_point_y] = 0.058;
    for (const char* k : {"A", "B", "C", "D"}) c.pred[{k, "korzen"}][Quantity::impact_point_y] = 0.051;
    const auto f = c.check();
    BOOST_TEST(claim(f, 5, 0).holds);
    BOOST_TEST(!claim(f, 5, 1).holds);
    BOOST_TEST(!claim(f, 5, 2).holds);
    BOOST_TEST(!claim(f, 5, 2).undecided);  // 4 mm better everywhere: the opposite, decided
  }
}

// Finding 5's "0.5 h_b increases the error" needs a margin: the mean excess |E| over CEMA beyond two
// standard uncertainties. A tie (the liggghts-rig case: 5.960 vs 5.950 mm, worse at half the
// conditions) is undecided, never reproduced; a clear excess holds even if one condition is better;
// a consistent but small excess is undecided when the measurement between the two predictions is
// too uncertain to tell them apart.
BOOST_AUTO_TEST_CASE(impact_point_tie_is_not_reproduced) {
  {
    Case c;  // measured 50 mm, Booth/CEMA 55 mm (|E| 5): Korzen 10.01 / 0.01 mm off in turn, mean 5.01
    const std::map<std::string, double> k{{"A", 0.06001}, {"B", 0.05001}, {"C", 0.06001}, {"D", 0.05001}};
    for (const auto& [name, y] : k) c.pred[{name, "korzen"}][Quantity::impact_point_y] = y;
    const auto f = c.check();
    const auto& cl = claim(f, 5, 2);
    BOOST_TEST_MESSAGE(cl.evidence);
    BOOST_TEST(cl.testable);
    BOOST_TEST(!cl.holds);
    BOOST_TEST(cl.undecided);
    BOOST_TEST(cl.evidence.find("undecided") != std::string::npos);
    BOOST_TEST((f[4].status == FindingStatus::partly));  // the other two claims still hold
    BOOST_TEST((f[4].status != FindingStatus::reproduced));
  }
  {
    Case c;  // 5 mm worse at three conditions, 1 mm better at one: mean +3.5 > 2 x 1.5 mm
    c.pred[{"D", "korzen"}][Quantity::impact_point_y] = 0.054;
    const auto f = c.check();
    BOOST_TEST_MESSAGE(claim(f, 5, 2).evidence);
    BOOST_TEST(claim(f, 5, 2).holds);
    BOOST_TEST(!claim(f, 5, 2).undecided);
  }
  {
    Case c;  // 0.5 mm worse everywhere, but the measurement (± 1 mm) lies between the predictions
    for (const char* k : {"A", "B", "C", "D"}) {
      c.pred[{k, "booth-cema"}][Quantity::impact_point_y] = 0.04975;
      c.pred[{k, "korzen"}][Quantity::impact_point_y] = 0.05075;
      c.impact_u[k] = 0.001;
    }
    const auto f = c.check();
    BOOST_TEST_MESSAGE(claim(f, 5, 2).evidence);
    BOOST_TEST(!claim(f, 5, 2).holds);
    BOOST_TEST(claim(f, 5, 2).undecided);
    for (const char* k : {"A", "B", "C", "D"}) c.impact_u[k] = 0.00001;  // the same, measured precisely
    BOOST_TEST(c.check()[4].claims.at(2).holds);
  }
}

BOOST_AUTO_TEST_CASE(missing_models_and_measurements_are_untestable_not_failed) {
  Case c;
  c.r.models = {"booth-cema", "korzen"};
  for (const char* k : {"A", "B", "C", "D"}) {
    c.pred.erase({k, "dem"});
    c.meas[k][Quantity::shear_force].reset();
  }
  const auto f = c.check();
  BOOST_TEST((f[2].status == FindingStatus::not_testable));
  BOOST_TEST((f[3].status == FindingStatus::not_testable));
  BOOST_TEST(!claim(f, 2, 1).testable);  // DEM ratio
  BOOST_TEST(!claim(f, 2, 2).testable);  // measured ratio needs R_s
  BOOST_TEST((f[1].status == FindingStatus::reproduced));  // Korzen's constant ratio alone
  BOOST_TEST(!claim(f, 5, 1).testable);
}
