// A station run that continues another's final state (dem/station/run.h Restart): with nothing
// changed it is the longer run itself, sample for sample; with a change it looks for its window only
// after the change has reached the plate; and the validation layer continues only runs whose
// difference can act on a running station.
#define BOOST_TEST_MODULE dem_station_restart
#include <boost/test/unit_test.hpp>

#include <filesystem>

#include <fmt/format.h>
#include <unistd.h>

#include "dem/station/run.h"
#include "effects/registry.h"
#include "tiny_station.h"
#include "validation/models/dem_model.h"

using namespace chutelab;
using namespace chutelab::dem::station;

namespace {

std::string temp_state(const char* name) {
  return (std::filesystem::temp_directory_path() / fmt::format("chutelab-test-{}-{}.state", name, ::getpid())).string();
}

validation::DemEffectInputs inputs(const std::string& effect) {
  analytical::EffectList fx;
  if (!effect.empty()) fx = effects::instantiate({effects::parse_setting(effect, false)});
  return validation::dem_effect_inputs(test::tiny_station(), fx);
}

}  // namespace

// The state saved at the end of a 0.3 s run, continued with the same inputs, gives the plate load
// of a 0.8 s run from empty at every sample after 0.3 s, bit for bit: the checkpoint
// holds everything the next step reads, and the stale contact lists of the last discharge are
// rebuilt before saving as the next step would. A restart that lost a contact's history or an
// inserter's random state would differ within a few samples.
BOOST_AUTO_TEST_CASE(continuing_a_state_is_the_longer_run) {
  const std::string state = temp_state("continue");
  RunOptions first;
  first.settings = test::tiny_settings();
  first.settings.max_time = 0.3;  // before min_time (0.4 s): no early stop
  first.settings.min_window = 0.2;
  first.save_state = state;
  const StationResult a = run_station(test::tiny_station(), first);

  RunOptions longer;
  longer.settings = test::tiny_settings();
  longer.settings.max_time = 0.8;
  longer.settings.min_time = 0.8;  // the whole 0.8 s
  const StationResult whole = run_station(test::tiny_station(), longer);

  RunOptions cont = longer;
  cont.restart = Restart{state, ChangeAt::plate};
  cont.settings.min_time = 0.1;  // a restart may run its transit and 0.7 s more; it stops once steady
  const StationResult b = run_station(test::tiny_station(), cont);
  BOOST_TEST(b.restart_time == a.simulated_time);
  BOOST_REQUIRE(!b.forces.empty());
  BOOST_TEST(b.forces.front().t > a.simulated_time);
  std::size_t matched = 0;
  for (const auto& s : b.forces)
    for (const auto& w : whole.forces)
      if (w.t == s.t) {
        BOOST_TEST(w.normal == s.normal);
        BOOST_TEST(w.shear == s.shear);
        BOOST_TEST(w.moment == s.moment);
        ++matched;
      }
  BOOST_TEST_MESSAGE(matched << " samples after the restart at " << a.simulated_time << " s compared");
  BOOST_TEST(matched == b.forces.size());
  BOOST_TEST(matched >= 100u);  // at least the transit and the 0.3 s window, in 3 ms samples
  std::filesystem::remove(state);
}

// A change at the feed needs the belt's transit and the flight before the plate sees it: the window
// starts no earlier (restart_transit), and the transit is longer than a flight change's, which is
// longer than a plate change's (one detection block). The mass balance still closes: the discharge
// before the restart is accounted for.
BOOST_AUTO_TEST_CASE(a_change_is_measured_after_it_reaches_the_plate) {
  const std::string state = temp_state("transit");
  RunOptions base;
  base.settings = test::tiny_settings();
  base.save_state = state;
  const StationResult b = run_station(test::tiny_station(), base);

  const auto fx = inputs("mass_flow_bias=-0.1");
  RunOptions o;
  o.settings = test::tiny_settings();
  o.external = fx.external;
  o.restart = Restart{state, ChangeAt::feed};
  const StationResult r = run_station(fx.station, o);
  BOOST_TEST(r.window.start >= r.transient_end - 1e-9);
  BOOST_TEST(r.transient_end > r.restart_time + 0.15);  // 0.35 m of belt and 0.35 m of flight at 3 m/s
  const Scene sc = build_scene(fx.station, o.settings, {}, fx.external);
  BOOST_TEST(restart_transit(sc, o.settings, ChangeAt::feed) > restart_transit(sc, o.settings, ChangeAt::flight));
  BOOST_TEST(restart_transit(sc, o.settings, ChangeAt::flight) > restart_transit(sc, o.settings, ChangeAt::plate));
  BOOST_TEST(restart_transit(sc, o.settings, ChangeAt::plate) == o.settings.detect_block);
  // 10 % less feed: the plate's normal load follows (from ~b's value, within a few se).
  BOOST_REQUIRE(r.normal_force.ok() && b.normal_force.ok());
  BOOST_TEST(r.normal_force.value < b.normal_force.value);
  BOOST_TEST(std::abs(r.inserted - r.discharged - r.escaped - r.in_domain) < 1e-9 * r.inserted);
  std::filesystem::remove(state);
}

// Only what can act on a running station is continued: the flow fed and the belt's adhesion (from
// the feed), a flight force, the plate friction. A moved plate or another belt speed is another rig
// (or another time step): those runs start from empty. Nothing changed is the run itself.
BOOST_AUTO_TEST_CASE(which_runs_continue) {
  const auto base = inputs("");
  auto at = [&](const std::string& e) { return validation::restart_change(base, inputs(e)); };
  BOOST_TEST((at("mass_flow_bias=-0.1") == ChangeAt::feed));
  BOOST_TEST((at("belt_adhesion=40") == ChangeAt::feed));
  BOOST_TEST((at("air_drag=0.7") == ChangeAt::flight));
  BOOST_TEST((at("plate_friction=0.1") == ChangeAt::plate));
  BOOST_TEST(!at("plate_distance=10").has_value());
  BOOST_TEST(!at("belt_slip=0.05").has_value());
  BOOST_TEST(!at("load_cell_offset=5").has_value());  // the DEM run is the baseline's
}
