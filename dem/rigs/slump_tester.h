#pragma once
// The swing-arm slump tester of the reference study (Grima & Wypych 2010, §5, Fig. 5): a 60 mm I.D. split tube
// rests on a bed of the same material in a 150 mm I.D. pipe; the sample is poured into the tube and
// settles, the loose-poured bulk density is measured, the swing arm opens the tube, the material flows
// out rapidly and forms a conical pile whose height (and angle of repose) is measured. The tester is
// designed so that particle-particle interactions dominate (the pile forms on a bed of grains, not on
// a wall): it calibrates the particle-particle rolling friction and the solid density (reference study Table 3).
//
// DEM set-up and its simplifications (stated in reports):
//  - the bed is a fixed rough floor: one hexagonal layer of glued grains of the same size and
//    material, spacing one diameter, covering the 150 mm pipe (a loose bed would cost ~2000 more
//    particles and hardly changes a pile formed on it; glued = infinite mass and inertia);
//  - the split tube is two half-cylinder meshes whose bottom edge sits on the bed crests; "opening" =
//    the halves move apart horizontally (normal to the split plane) at open_speed, like the ends of two
//    long swing arms, and are parked out of the way once clear of the pipe;
//  - the sample is placed on a jittered lattice inside the tube and released (a loose pour from
//    about one tube diameter), then settles.
// Measurements:
//  - bulk density: mass per volume of the tube's core (between one grain above the tube's bottom edge
//    and 1.5 grains below the mean top surface, the wall layer included as in the lab tube); fill
//    height H = the height the sample fills at that density (a dividing surface: the grain-scale
//    roughness of the poured top would otherwise bias a "level" by up to half a grain);
//  - angle of repose: straight-line fit of the surface profile (mean cell top in radial bins) over the
//    flank, where the profile lies between 20 % and 80 % of the peak (the highest grain top within 2 d
//    of the axis above the bed crests);
//  - pile height: that line at the axis, the apex of the fitted cone (the peak itself when the flank
//    has too few bins). Why not the peak: one grain more or less on the tip moves it by ~5 % from pour
//    to pour (5 seeds, spheres, mu_r 0.1: sd 1.2 mm), as much as mu_r 0.05 -> 0.1 changes the pile;
//    the apex of the fit uses the whole flank (sd 0.7 mm) and separates mu_r 0.05 from 0.2 by 7 sd.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "core/rig.h"
#include "dem/rigs/grain.h"

namespace chutelab::dem::rigs {

struct SlumpSettings {
  double tube_diameter = 0.060;   // m, I.D. of the split tube (reference study Fig. 5)
  double pipe_diameter = 0.150;   // m, I.D. of the pipe holding the bed (reference study Fig. 5)
  double fill_height = 0.030;     // m of settled material aimed for (particle count from a 0.58 guess)
  double modulus_scale = 1.0;     // multiplies Young's modulus (softer = longer time step)
  double open_speed = 0.5;        // m/s of each half of the tube
  double settle_speed = 0.01;     // m/s: settled when no grain moves faster
  double min_settle_time = 0.15;  // s
  double max_settle_time = 0.6;   // s
  double min_pile_time = 0.25;    // s after opening
  double max_pile_time = 1.2;     // s after opening
  double wall_friction = -1.0;    // particle-tube sliding friction; < 0: the material's friction_side
                                  // (or friction_plate when that is 0)
  RollingModel rolling = RollingModel::constant_torque;
  int threads = 1;
  std::uint64_t seed = 1;
};

enum class RigQuality { quick, standard };
// quick: 45 mm fill (~800 spheres of 5.6 mm), Young's modulus / 100; standard: 60 mm fill, modulus / 10.
SlumpSettings slump_preset(RigQuality q);

struct ProfilePoint {
  double r = 0.0;  // m from the axis (bin centre)
  double h = 0.0;  // m, mean surface height above the bed crests
  int cells = 0;
};

struct SlumpResult {
  std::string grain;
  std::size_t particles = 0;     // grains in the sample
  std::size_t bed_grains = 0;
  double sample_mass = 0.0;      // kg
  double fill_height = 0.0;      // m, sample mass / (tube area x bulk density)
  double surface_height = 0.0;   // m, mean of the highest grain tops in 1.5 d cells (rough envelope)
  double bulk_density = 0.0;     // kg/m^3, loose poured
  double pile_height = 0.0;      // m above the bed crests: apex of the cone fitted to the flank
  double repose_angle_deg = 0.0; // from the flank fit (NaN when the flank has < 3 bins)
  double pile_radius = 0.0;      // m, where the profile falls below one grain diameter
  double peak_height = 0.0;      // m, highest grain top within 2 d of the axis above the bed crests
  double lost_mass = 0.0;        // kg that fell off the bed
  std::vector<ProfilePoint> profile;
  double dt = 0.0, settle_time = 0.0, pile_time = 0.0;  // s
  long long steps = 0;
  double wall_seconds = 0.0;
  bool settled = true;           // both phases ended by the settle criterion, not the time limit
};

struct SlumpProgress {
  std::string phase;  // "pour", "slump"
  double time = 0.0, max_time = 0.0;
};

// Runs one slump test. `m` supplies E, nu, frictions, restitutions; density and rolling friction are
// taken from the arguments (the calibration sweeps them). Throws InputError for impossible settings.
SlumpResult run_slump_test(const chutelab::Material& m, double solid_density, double rolling_friction, const Grain& g,
                           const SlumpSettings& s, const std::function<void(const SlumpProgress&)>& progress = {});

}  // namespace chutelab::dem::rigs
