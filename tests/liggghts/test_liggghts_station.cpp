// LIGGGHTS as the station's engine on the tiny station (tests/dem_station/tiny_station.h): the run
// goes through, chutelab's sensors find in its output the identities every station obeys, and it
// agrees with the built-in DEM on the same station. Needs LIGGGHTS (found by CMake, or `liggghts` on
// PATH); without it every case exits with status 77, which ctest reports as skipped.
#define BOOST_TEST_MODULE liggghts_station
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <unistd.h>

#include "dem/liggghts/run.h"
#include "dem/station/run.h"
#include "../dem_station/tiny_station.h"

using namespace chutelab;
using namespace chutelab::dem;

namespace {

constexpr int kSkipped = 77;  // SKIP_RETURN_CODE in tests/liggghts/CMakeLists.txt

std::string program() { return CHUTELAB_LIGGGHTS[0] ? CHUTELAB_LIGGGHTS : "liggghts"; }

void require_liggghts() {
  if (liggghts::version(program()).empty()) {
    std::cout << "LIGGGHTS not found ('" << program() << "'): skipped\n";
    std::exit(kSkipped);
  }
}

station::RunSettings settings(NormalLaw law) {
  station::RunSettings s = test::tiny_settings();
  s.contact = law;
  return s;
}

// The tiny station through LIGGGHTS with the given law (once per law and process).
station::StationResult run_liggghts(NormalLaw law) {
  liggghts::Options o;
  o.settings = settings(law);
  o.command = "mpirun -n 1 " + program();
  // Per process: sessions sharing the machine run the suite at the same time.
  o.work_dir = (std::filesystem::temp_directory_path() /
                ("chutelab-test-liggghts-tiny-" + std::string(law.key()) + "-" + std::to_string(::getpid())))
                   .string();
  station::StationResult r = liggghts::run_station(test::tiny_station(), o);
  std::filesystem::remove_all(o.work_dir);  // the dump is megabytes; the result holds what the tests read
  return r;
}

station::StationResult run_builtin(NormalLaw law) {
  station::RunOptions o;
  o.settings = settings(law);
  return station::run_station(test::tiny_station(), o);
}

const station::StationResult& lig() {
  static const station::StationResult r = run_liggghts(NormalLaw{});
  return r;
}

const station::StationResult& builtin() {
  static const station::StationResult r = run_builtin(NormalLaw{});
  return r;
}

}  // namespace

BOOST_AUTO_TEST_CASE(runs_to_a_steady_state) {
  require_liggghts();
  const auto& r = lig();
  BOOST_TEST_MESSAGE("LIGGGHTS tiny: window " << r.window.start << "-" << r.window.end << " s, R_n " << r.normal_force.value
                                              << " +- " << r.normal_force.se << " N, y_R " << r.impact_point_y.value * 1e3
                                              << " mm, " << r.peak_particles << " particles, " << r.wall_seconds << " s");
  BOOST_TEST(r.window.found);
  BOOST_TEST(r.normal_force.value > 0.0);
  BOOST_TEST(r.normal_force.se < 0.05 * r.normal_force.value);
  BOOST_TEST(r.inserted > 1.0);
  BOOST_TEST(r.discharged > 0.2 * r.inserted);
}

// The plate's normal force equals the x-momentum the stream carries into the control volume in
// front of it (dem_station_physics: the same identity in the built-in DEM). It holds in any engine,
// so it checks what chutelab reads from LIGGGHTS: the force's sign and averaging, and the particle
// frames matched by id. Tolerance 3 %: as the built-in's 2 %, plus the dump's 6-digit positions.
BOOST_AUTO_TEST_CASE(plate_force_equals_momentum_flux) {
  require_liggghts();
  const auto& r = lig();
  BOOST_TEST_MESSAGE("R_n " << r.normal_force.value << " N, momentum delivered " << r.momentum_balance.value << " N");
  BOOST_TEST(std::abs(r.momentum_balance.value / r.normal_force.value - 1.0) < 0.03);
  // The feed's 2.5 kg/s crosses x = Z/2 (3 %: as dem_station_physics).
  BOOST_TEST(std::abs(r.mass_flux.value / 2.5 - 1.0) < 0.03, "mass flux " << r.mass_flux.value);
  // The layer reaches the pulley at belt speed (3 m/s; 2 %).
  BOOST_TEST(std::abs(r.layer_speed.value / 3.0 - 1.0) < 0.02, "layer speed " << r.layer_speed.value);
}

// Two engines, one station: R_n within 5 % (the statistical error of each is ~1 %; the engines
// differ in how inserted particles start and in their contact details, README "LIGGGHTS on a
// cluster"), the impact point within 5 mm (0.4 d).
BOOST_AUTO_TEST_CASE(agrees_with_the_builtin_dem) {
  require_liggghts();
  const auto &a = lig(), &b = builtin();
  BOOST_TEST_MESSAGE("R_n LIGGGHTS " << a.normal_force.value << " / built-in " << b.normal_force.value
                     << " N; y_R " << a.impact_point_y.value * 1e3 << " / " << b.impact_point_y.value * 1e3 << " mm");
  BOOST_TEST(std::abs(a.normal_force.value / b.normal_force.value - 1.0) < 0.05);
  BOOST_TEST(std::abs(a.impact_point_y.value - b.impact_point_y.value) < 0.005);
}

// The same with the Hooke law (dem/contact/hooke.h), whose deck LIGGGHTS reads as hooke/stiffness
// with the law's own kn, kt, gamman and gammat per type pair (the registry's LIGGGHTS mapping): the
// same tolerances.
BOOST_AUTO_TEST_CASE(hooke_agrees_with_the_builtin_dem) {
  require_liggghts();
  const auto hooke = NormalLaw::of<Hooke>();
  const auto a = run_liggghts(hooke), b = run_builtin(hooke);
  BOOST_TEST_MESSAGE("hooke: R_n LIGGGHTS " << a.normal_force.value << " / built-in " << b.normal_force.value
                     << " N; y_R " << a.impact_point_y.value * 1e3 << " / " << b.impact_point_y.value * 1e3 << " mm");
  BOOST_TEST(a.normal_force.value > 0.0);
  BOOST_TEST(std::abs(a.normal_force.value / b.normal_force.value - 1.0) < 0.05);
  BOOST_TEST(std::abs(a.impact_point_y.value - b.impact_point_y.value) < 0.005);
}

// Asking LIGGGHTS for its version (every cache key does) leaves nothing behind in the working
// directory: LIGGGHTS opens log.liggghts there unless told not to.
BOOST_AUTO_TEST_CASE(version_probe_writes_no_log) {
  require_liggghts();
  namespace fs = std::filesystem;
  const fs::path here = fs::current_path();
  const fs::path dir = fs::temp_directory_path() / ("chutelab-test-liggghts-version-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  fs::remove(dir / "log.liggghts");
  fs::current_path(dir);
  const std::string v = liggghts::version(program());
  fs::current_path(here);
  BOOST_TEST(v.find("LIGGGHTS") != std::string::npos);
  BOOST_TEST(!fs::exists(dir / "log.liggghts"));
  fs::remove_all(dir);
}
