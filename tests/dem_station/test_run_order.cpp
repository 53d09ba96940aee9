// A run's numbers must not depend on what ran before it in the process. The
// sensitivity study runs variants one after another; here the same 9 mm run is made first in a
// fresh state and again after runs of 13.6 mm spheres and of clumps (which leave larger per-thread
// scratch, other neighbour-list sizes and another contact law behind), and must agree bit for bit.
#define BOOST_TEST_MODULE dem_station_run_order
#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <cstring>

#include "dem/station/run.h"
#include "tiny_station.h"

using namespace chutelab;
using namespace chutelab::dem::station;

namespace {

StationResult run(double diameter, ParticleShape shape, ContactLaw law, int threads) {
  RunOptions o;
  o.settings = test::tiny_settings();
  o.settings.max_time = 0.3;  // the stream reaches the plate after ~0.2 s: some samples carry its force
  o.settings.min_window = 0.05;
  o.settings.particle_diameter = diameter;
  o.settings.particle_shape = shape;
  o.settings.contact = law;
  o.settings.threads = threads;
  o.settings.seed = 3;
  return run_station(test::tiny_station(), o);
}

void same_bits(const StationResult& a, const StationResult& b) {
  BOOST_REQUIRE_EQUAL(a.forces.size(), b.forces.size());
  BOOST_REQUIRE(!a.forces.empty());
  double peak = 0.0;  // equal zeros would prove nothing: the plate must have been hit
  for (const auto& f : a.forces) peak = std::max(peak, f.normal);
  BOOST_REQUIRE(peak > 0.0);
  std::size_t differ = 0;
  for (std::size_t k = 0; k < a.forces.size(); ++k)
    differ += std::memcmp(&a.forces[k].normal, &b.forces[k].normal, sizeof(double)) != 0 ||
              std::memcmp(&a.forces[k].shear, &b.forces[k].shear, sizeof(double)) != 0;
  BOOST_TEST(differ == 0u, differ << " of " << a.forces.size() << " force samples differ");
  BOOST_TEST(a.steps == b.steps);
  BOOST_TEST(a.peak_particles == b.peak_particles);
}

}  // namespace

BOOST_AUTO_TEST_CASE(a_run_does_not_depend_on_the_runs_before_it) {
  // One thread: the thread-count independence has its own test (dem_station_physics).
  for (int threads : {1}) {
    BOOST_TEST_CONTEXT("threads " << threads) {
      const auto fresh = run(9e-3, ParticleShape::sphere, dem::NormalLaw::of<dem::HertzMindlin>(), threads);
      (void)run(13.6e-3, ParticleShape::sphere, dem::NormalLaw::of<dem::HertzMindlin>(), threads);
      (void)run(9e-3, ParticleShape::clump, dem::NormalLaw::of<dem::LinearSpringDashpot>(), threads);
      const auto after = run(9e-3, ParticleShape::sphere, dem::NormalLaw::of<dem::HertzMindlin>(), threads);
      same_bits(fresh, after);
    }
  }
}
