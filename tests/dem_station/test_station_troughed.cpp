// The transfer station on a 3-roll troughed belt (20° idlers, 100 mm centre roll, wings flattening
// over the last stretch before the pulley), run long enough to be steady. The flat-belt checks of
// test_station_physics.cpp must hold here too: what goes in comes out, the layer reaches the pulley
// at belt speed although it rode in a trough, and the vertical plate feels the momentum it is
// brought. A trough whose wings did not move with the belt, or a transition that held particles
// back, would fail the speed and mass checks.
#define BOOST_TEST_MODULE dem_station_troughed
#include <boost/test/unit_test.hpp>

#include <cmath>

#include "dem/station/run.h"
#include "tiny_station.h"

using namespace chutelab;
using namespace chutelab::dem::station;

namespace {

Station troughed_station() { return test::tiny_troughed_station(); }

const StationResult& troughed_run() {
  static const StationResult r = [] {
    RunOptions o;
    o.settings = test::tiny_settings();
    return run_station(troughed_station(), o);
  }();
  return r;
}

}  // namespace

BOOST_AUTO_TEST_CASE(troughed_belt_reaches_a_steady_state) {
  const auto& r = troughed_run();
  BOOST_TEST_MESSAGE("steady window " << r.window.start << "-" << r.window.end << " s, R_n = " << r.normal_force.value
                                      << " +- " << r.normal_force.se << " N, layer speed " << r.layer_speed.value
                                      << " m/s, " << r.wall_seconds << " s wall");
  BOOST_TEST(r.window.found);
  BOOST_TEST(r.normal_force.value > 0.0);
}

// Tolerances as for the flat belt: sums to round-off; the steady stream carries the feed rate within
// 3 % (particles rebounding across x = Z/2 are counted twice).
BOOST_AUTO_TEST_CASE(troughed_belt_conserves_mass) {
  const auto& r = troughed_run();
  BOOST_TEST(r.escaped == 0.0);
  BOOST_TEST(r.discharged > 0.2 * r.inserted);
  BOOST_TEST(std::abs(r.inserted - (r.discharged + r.escaped + r.in_domain)) < 1e-9 * r.inserted);
  BOOST_TEST(std::abs(r.mass_flux.value / troughed_station().mass_flow - 1.0) < 0.03,
             "mass flux " << r.mass_flux.value << " kg/s");
}

// The reference study's no-slip discharge: settled particles ride at the belt's speed through the transition.
// Tolerance 1 %, as on the flat belt.
BOOST_AUTO_TEST_CASE(troughed_layer_reaches_the_pulley_at_belt_speed) {
  const auto& r = troughed_run();
  BOOST_TEST(std::abs(r.layer_speed.value / troughed_station().belt_speed - 1.0) < 0.01);
}

// Vertical plate: R_n equals the x-momentum delivered to the control volume in front of it. 2 %,
// the sampling tolerance of the flat-belt test.
BOOST_AUTO_TEST_CASE(troughed_plate_force_equals_momentum_flux) {
  const auto& r = troughed_run();
  BOOST_TEST_MESSAGE("R_n = " << r.normal_force.value << " N, momentum delivered " << r.momentum_balance.value << " N");
  BOOST_TEST(std::abs(r.momentum_balance.value / r.normal_force.value - 1.0) < 0.02);
}
