// The transfer-station DEM fed with the reference study's two-sphere pellets (Fig. 4c) instead of spheres, on the
// tiny station of the dem-station tests: mass is conserved with bodies that leave whole, the plate
// feels the momentum the stream brings, and the shape is part of the settings' cache key. One DEM run
// (~0.75 s simulated, a few seconds of CPU) is shared by the checks.
#define BOOST_TEST_MODULE dem_station_clumps
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "core/input_error.h"
#include "dem/station/run.h"
#include "dem/station/settings.h"
#include "../dem_station/tiny_station.h"
#include "validation/models/dem_model.h"

using namespace chutelab;
using namespace chutelab::dem::station;
namespace fs = std::filesystem;

namespace {

RunSettings clump_settings() {
  RunSettings s = test::tiny_settings();
  s.particle_shape = ParticleShape::clump;
  return s;
}

const StationResult& clump_run() {
  static const StationResult r = [] {
    RunOptions o;
    o.settings = clump_settings();
    return run_station(test::tiny_station(), o);
  }();
  return r;
}

}  // namespace

// The run is made of clumps: twice as many spheres as bodies, a steady plate force.
BOOST_AUTO_TEST_CASE(clump_run_reaches_a_steady_state) {
  const auto& r = clump_run();
  BOOST_TEST_MESSAGE("clumps: steady window " << r.window.start << "-" << r.window.end << " s, R_n = "
                                              << r.normal_force.value << " +- " << r.normal_force.se << " N, "
                                              << r.peak_particles << " spheres, " << r.wall_seconds << " s wall");
  BOOST_TEST(r.shape == "clump");
  bool said = false;
  for (const auto& n : r.notes) said = said || n.find("two-sphere clumps") != std::string::npos;
  BOOST_TEST(said);
  BOOST_TEST(r.window.found);
  BOOST_TEST(r.normal_force.value > 0.0);
}

// Everything the feed inserted was discharged below the plate or is still in the rig, counting whole
// bodies (a clump leaves as soon as one of its spheres is below the sink). Tolerance: round-off of the
// sums (1e-9 relative); a body counted by its spheres below the sink only would miss ~half its mass per
// discharged clump, ~1e-3 of the total. The stream carries the feed rate: 3 % as for spheres (a few
// rebounding grains cross twice; a body's two spheres cross the plane a step or two apart).
BOOST_AUTO_TEST_CASE(clump_run_conserves_mass) {
  const auto& r = clump_run();
  BOOST_TEST_MESSAGE("inserted " << r.inserted << " kg, discharged " << r.discharged << ", escaped " << r.escaped
                                 << ", in the rig " << r.in_domain << "; mass flux " << r.mass_flux.value << " kg/s");
  BOOST_TEST(r.inserted > 1.0);
  BOOST_TEST(r.discharged > 0.2 * r.inserted);
  BOOST_TEST(r.escaped == 0.0);
  BOOST_TEST(std::abs(r.inserted - (r.discharged + r.escaped + r.in_domain)) < 1e-9 * r.inserted);
  // The feed keeps the condition's mass flow (2.5 kg/s) with heavier bodies: what was inserted over
  // the run is the rate times the time, less at most one body owed at the end (~1.2e-3 kg) and the
  // insertion interval's share.
  BOOST_TEST(std::abs(r.inserted / (2.5 * r.simulated_time) - 1.0) < 0.01);
  BOOST_TEST(std::abs(r.mass_flux.value / 2.5 - 1.0) < 0.03);
}

// The plate's normal force equals the x-momentum flux the stream carries into the control volume in
// front of it (the same balance as for spheres, test_station_physics.cpp). Counted per member sphere
// with its share of the body's mass, the flux of a body is its own when both spheres are on the same
// side of a plane; a body straddling it for a step shifts momentum between neighbouring samples only.
// Tolerance 3 %: the spheres' 2 % plus the straddling bodies.
BOOST_AUTO_TEST_CASE(clump_plate_normal_force_equals_momentum_flux) {
  const auto& r = clump_run();
  BOOST_TEST_MESSAGE("R_n = " << r.normal_force.value << " N, momentum delivered " << r.momentum_balance.value
                              << " N, free-stream estimate m V_b = " << 2.5 * 3.0 << " N");
  BOOST_TEST(std::abs(r.momentum_balance.value / r.normal_force.value - 1.0) < 0.03);
  // And the sensors that the report draws from work on clumps too.
  BOOST_TEST(r.impact_velocity.ok());
  BOOST_TEST(r.impact_point_y.ok());
  BOOST_TEST(r.trajectory.size() >= 15u);
  BOOST_TEST(!r.side_view.empty());
}

// The shape changes the result, so it is part of the cache key; spheres keep the key they had. The
// [dem] table reads `shape` and refuses other values naming the key.
BOOST_AUTO_TEST_CASE(shape_is_in_the_cache_key_and_the_dem_table) {
  RunSettings sphere = test::tiny_settings(), clump = clump_settings();
  BOOST_TEST(canonical(sphere) != canonical(clump));
  BOOST_TEST(canonical(sphere).find("shape") == std::string::npos);
  validation::DemEffectInputs fx;
  fx.station = test::tiny_station();
  BOOST_TEST(validation::dem_cache_key(fx, sphere, {}) != validation::dem_cache_key(fx, clump, {}));

  const fs::path d = fs::temp_directory_path() / ("chutelab-station-clumps-" + std::to_string(::getpid()));
  fs::create_directories(d);
  std::ofstream(d / "setup.toml") << "name = \"x\"\n[dem]\nshape = \"clump\"\n";
  const RunSettings from_table = resolve(read_dem_table((d / "setup.toml").string()), {});
  BOOST_TEST((from_table.particle_shape == ParticleShape::clump));
  SettingsOverrides o;
  o.set("shape", "sphere");
  BOOST_TEST((resolve(read_dem_table((d / "setup.toml").string()), o).particle_shape == ParticleShape::sphere));
  std::ofstream(d / "bad.toml") << "name = \"x\"\n[dem]\nshape = \"cube\"\n";
  try {
    read_dem_table((d / "bad.toml").string());
    BOOST_FAIL("unknown shape accepted");
  } catch (const InputError& e) {
    BOOST_TEST(e.field() == "dem.shape");
    BOOST_TEST(e.line() == 3);
  }
  fs::remove_all(d);
}
