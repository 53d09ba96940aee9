#include <boost/test/unit_test.hpp>
#include <cmath>

#include "analytical/korzen.h"
#include "analytical/transfer_station.h"
#include "validation/dataset.h"

using namespace chutelab;
using namespace chutelab::analytical;
namespace tt = boost::test_tools;

namespace {
constexpr double pi = 3.14159265358979323846;
}

BOOST_AUTO_TEST_SUITE(korzen)

BOOST_AUTO_TEST_CASE(hand_calculation_with_stationary_flow) {
  // m_s = 10 kg/s, V_p = 2.5 m/s at alpha_p = 36 deg on a vertical plate, mu_pw = 0.27:
  // V_pn = 2.5 cos36 = 2.02254, V_pt = 2.5 sin36 = 1.46946; 36 > atan(0.27) = 15.11 -> stationary.
  // Eq 4 with continuity converges to V_a = V_p (sin36 - 0.27 cos36) = 2.5 (0.58779 - 0.21843)
  // = 0.92339 m/s. R_n = 10 * 2.02254 = 20.2254 N; R_s = m (V_pt - V_a) = 5.4607 N.
  const double a = 36.0 * pi / 180;
  const KorzenResult r = korzen_impact({10.0, 540.0, 2.5, a, 0.0, 0.27, 0.0});
  BOOST_TEST(r.stationary_flow);
  BOOST_TEST(r.normal_speed == 2.5 * std::cos(a), tt::tolerance(1e-12));
  BOOST_TEST(r.tangential_speed == 2.5 * std::sin(a), tt::tolerance(1e-12));
  BOOST_REQUIRE(r.exit_speed);
  BOOST_TEST(*r.exit_speed == 2.5 * (std::sin(a) - 0.27 * std::cos(a)), tt::tolerance(1e-10));
  BOOST_TEST(*r.exit_speed == 0.92339, tt::tolerance(1e-4));
  BOOST_TEST(r.iterations > 5);  // it really iterated from A_a = A_p
  BOOST_TEST(r.normal_force == 10.0 * 2.5 * std::cos(a), tt::tolerance(1e-12));  // Eq 5
  BOOST_TEST((r.shear_equation == ShearEquation::eq6));
  BOOST_TEST(r.shear_force == 10.0 * (2.5 * std::sin(a) - *r.exit_speed), tt::tolerance(1e-10));
  BOOST_TEST(r.shear_force / r.normal_force == 0.27, tt::tolerance(1e-9));
  BOOST_TEST(r.resultant_force == std::hypot(r.normal_force, r.shear_force), tt::tolerance(1e-12));
  // Continuity closes: rho_bl A_a V_a = m_s.
  BOOST_TEST(540.0 * *r.outflow_area * *r.exit_speed == 10.0, tt::tolerance(1e-9));
}

BOOST_AUTO_TEST_CASE(stationary_flow_switches_at_atan_mu) {
  const double mu = 0.27, edge = std::atan(mu);
  const KorzenResult above = korzen_impact({10.0, 540.0, 4.0, edge + 1e-6, 0.0, mu, 0.0});
  const KorzenResult below = korzen_impact({10.0, 540.0, 4.0, edge - 1e-6, 0.0, mu, 0.0});
  BOOST_TEST(above.stationary_flow);
  BOOST_TEST(above.exit_speed.has_value());
  BOOST_TEST(!below.stationary_flow);
  BOOST_TEST(!below.exit_speed.has_value());  // the "negative root": Eq 4 has no solution
  BOOST_TEST((below.shear_equation == ShearEquation::eq7));
  BOOST_TEST(below.shear_force == mu * below.normal_force, tt::tolerance(1e-12));
  // The plate angle adds to the impact angle (alpha_p + beta): a 10 deg plate lifts 10 deg stream
  // above the threshold.
  const KorzenResult tilted = korzen_impact({10.0, 540.0, 4.0, 10.0 * pi / 180, 10.0 * pi / 180, mu, 0.0});
  BOOST_TEST(tilted.stationary_flow);
  BOOST_TEST(tilted.normal_speed == 4.0 * std::cos(20.0 * pi / 180), tt::tolerance(1e-12));
}

BOOST_AUTO_TEST_CASE(bundled_rig_reproduces_the_reference_findings) {
  // The reference study's findings 1 and 2: stationary flow at 2 and 3 m/s, not at 4 and 5 m/s; R_s/R_n = mu_pw.
  const auto d = validation::read_dataset(CHUTELAB_SOURCE_DIR "/datasets/grima2010",
                                          validation::MeasurementsRequired::no);
  BOOST_REQUIRE_EQUAL(d.stations.size(), 8u);
  for (const auto& st : d.stations) {
    const auto a = analyse_transfer(st);
    BOOST_TEST_CONTEXT(st.condition) {
      BOOST_TEST(a.korzen.stationary_flow == (st.belt_speed < 3.5));
      BOOST_TEST(a.korzen.shear_force / a.korzen.normal_force == st.material.friction_plate,
                 tt::tolerance(1e-9));
      BOOST_TEST((a.korzen.shear_equation ==
                 (st.belt_speed < 3.5 ? ShearEquation::eq6 : ShearEquation::eq7)));
      // V_p from the trajectory equals the energy form of reference study Eqs 1-2: V_p^2 = V_d^2 + 2 g s.
      const auto& k = a.line(Streamline::korzen_centroid);
      const double s = k.release.position.y() - k.hit->point.position.y();
      BOOST_TEST(k.hit->speed * k.hit->speed == st.belt_speed * st.belt_speed + 2 * st.gravity * s,
                 tt::tolerance(1e-10));
    }
  }
}

BOOST_AUTO_TEST_SUITE_END()
