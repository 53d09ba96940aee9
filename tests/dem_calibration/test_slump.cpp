// The swing-arm slump tester (reference study §5, Fig. 5) with a few hundred spheres: the poured sample packs
// loosely, and opening the tube leaves a conical pile whose height and flank can be measured.
#define BOOST_TEST_MODULE dem_slump
#include <boost/test/unit_test.hpp>

#include <cmath>

#include <fmt/format.h>

#include "dem/rigs/slump_tester.h"

using namespace chutelab;
using namespace chutelab::dem;
using namespace chutelab::dem::rigs;

namespace {

chutelab::Material pellets() {
  chutelab::Material m;
  m.particle_diameter = 4.55e-3;
  m.solid_density = 925;
  m.youngs_modulus = 2.5e8;
  m.poisson_ratio = 0.38;
  m.friction_particle = 0.3;
  m.friction_plate = 0.27;
  m.friction_side = 0.29;
  m.rolling_friction_particle = 0.1;
  m.restitution_particle = 0.7;
  m.restitution_plate = 0.66;
  return m;
}

SlumpSettings small() {
  SlumpSettings s = slump_preset(RigQuality::quick);
  s.fill_height = 0.030;  // ~540 spheres of 5.6 mm
  s.threads = 1;
  return s;
}

}  // namespace

// Loose packing: solid fraction rho_bulk / rho_s between 0.50 and 0.64 (random loose packing of
// frictional spheres is ~0.55-0.60, random close packing 0.64; a tube only ~11 diameters wide loosens
// the packing near its wall). The pile: its height is measurable (more than two grains, less than the
// fill, since the column spreads out) and its flank gives an angle of repose between 10 and 40 degrees
// (spheres with mu_r = 0.1 and mu = 0.3 pile at roughly 20-30 degrees).
BOOST_AUTO_TEST_CASE(slump_test_gives_loose_packing_and_a_measurable_pile) {
  const SlumpResult r = run_slump_test(pellets(), 1000.0, 0.1, Grain::sphere(5.6e-3), small());
  BOOST_TEST_MESSAGE(fmt::format(
      "{} grains (+{} bed), dt {:.3g} s, {} steps, {:.1f} s wall; fill {:.1f} mm, bulk {:.0f} kg/m^3 (phi {:.3f}); "
      "pile {:.1f} mm, repose {:.1f} deg, radius {:.0f} mm, lost {:.1f} g, settled {}",
      r.particles, r.bed_grains, r.dt, r.steps, r.wall_seconds, r.fill_height * 1e3, r.bulk_density,
      r.bulk_density / 1000.0, r.pile_height * 1e3, r.repose_angle_deg, r.pile_radius * 1e3, r.lost_mass * 1e3,
      r.settled));
  for (const auto& p : r.profile) BOOST_TEST_MESSAGE(fmt::format("  r {:5.1f} mm  h {:5.1f} mm", p.r * 1e3, p.h * 1e3));
  BOOST_TEST(r.particles > 300u);
  BOOST_TEST(r.particles < 700u);
  const double phi = r.bulk_density / 1000.0;
  BOOST_TEST(phi > 0.50);
  BOOST_TEST(phi < 0.64);
  BOOST_TEST(r.pile_height > 2 * 5.6e-3);
  BOOST_TEST(r.pile_height < r.fill_height);
  BOOST_TEST(std::isfinite(r.repose_angle_deg));
  BOOST_TEST(r.repose_angle_deg > 10.0);
  BOOST_TEST(r.repose_angle_deg < 40.0);
}

// The same tester filled with the reference study's two-sphere clumps (Fig. 4c): the clumps are poured, pack
// loosely (solid fraction 0.50-0.66: elongated grains pack a little denser than spheres, reference study §5) and
// slump into a pile with a flank.
BOOST_AUTO_TEST_CASE(slump_test_with_clumps) {
  SlumpSettings s = small();
  s.fill_height = 0.020;  // ~640 clumps of 2 x 4.4 mm
  const SlumpResult r = run_slump_test(pellets(), 1000.0, 0.1, Grain::reference_clump(), s);
  BOOST_TEST_MESSAGE(fmt::format("{}: {} grains, {:.1f} s wall; bulk {:.0f} kg/m^3, pile {:.1f} mm, repose {:.1f} deg",
                                 r.grain, r.particles, r.wall_seconds, r.bulk_density, r.pile_height * 1e3,
                                 r.repose_angle_deg));
  BOOST_TEST(r.bulk_density / 1000.0 > 0.50);
  BOOST_TEST(r.bulk_density / 1000.0 < 0.66);
  BOOST_TEST(r.pile_height > 2 * 4.4e-3);
  BOOST_TEST(std::isfinite(r.repose_angle_deg));
}
