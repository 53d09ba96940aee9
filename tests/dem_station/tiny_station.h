#pragma once
// A small, fast transfer station for the dem-station tests: a thin stream (2.5 kg/s at 3 m/s,
// ~1.5 layers of 13.6 mm spheres), a short belt and a wide plate the stream never spreads across,
// so the side panels stay out of the momentum balance. Material of the LIGGGHTS rig.
#include <cmath>

#include "core/rig.h"
#include "dem/station/run.h"

namespace chutelab::test {

inline Station tiny_station() {
  Station s;
  s.condition = "tiny";
  s.belt.pulley_diameter = 0.25;
  s.belt.belt_thickness = 0.005;
  s.belt.belt_width = 0.20;
  s.belt.loaded_width = 0.12;
  s.plate.width = 0.60;
  s.plate.height = 0.40;
  s.plate.angle = 0.0;
  auto& m = s.material;
  m.particle_diameter = 9e-3;
  m.solid_density = 1000.0;
  m.bulk_density = 558.0;
  m.youngs_modulus = 2.5e7;
  m.poisson_ratio = 0.38;
  m.friction_particle = 0.3;
  m.friction_plate = 0.27;
  m.friction_belt = 0.7;
  m.friction_side = 0.27;
  m.rolling_friction_particle = 0.1;
  m.rolling_friction_wall = 0.1;
  m.restitution_particle = 0.7;
  m.restitution_plate = 0.66;
  m.restitution_belt = 0.4;
  s.belt_speed = 3.0;
  s.mass_flow = 2.5;
  s.plate_distance = 0.35;
  s.plate_top = 0.25;
  return s;
}

// The tiny rig slowed to 1.2 m/s (1 kg/s: the same ~1.5 layers) with the plate at 250 mm. Here
// V_b^2 / (g r) is just above 1 for the bottom layer, so a small pull towards the pulley holds it past
// the tangent point (Booth's low-speed release): the scene where belt adhesion shows.
inline Station tiny_slow_station() {
  Station s = tiny_station();
  s.condition = "tiny-slow";
  s.belt_speed = 1.2;
  s.mass_flow = 1.0;
  s.plate_distance = 0.25;
  return s;
}

// The tiny station on a 3-roll troughed belt: 20° idlers, 100 mm centre roll, 20° surcharge, the
// wings flattening towards the pulley.
inline Station tiny_troughed_station() {
  Station s = tiny_station();
  s.belt.belt_width = 0.30;
  s.belt.loaded_width = 0.20;
  s.belt.trough.idler_angle = 20.0 * M_PI / 180.0;
  s.belt.trough.centre_roll = 0.10;
  s.belt.trough.surcharge_angle = 20.0 * M_PI / 180.0;
  return s;
}

// The quick preset, shortened: 0.75 s at most, a 0.3 s steady window.
inline dem::station::RunSettings tiny_settings() {
  auto s = dem::station::preset(dem::station::Quality::quick);
  s.max_time = 0.75;
  s.min_window = 0.3;
  s.threads = 1;
  return s;
}

}  // namespace chutelab::test
