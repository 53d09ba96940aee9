#pragma once
// The transfer station of one condition as a LIGGGHTS-PUBLIC 3.x input deck with ASCII STL meshes,
// written from the same Scene the built-in DEM runs (dem/station/scene.h): its walls, materials,
// feed, feeder relaxation, time step and domain. So both engines run one station, and the deck's
// outputs are measured by chutelab's own sensors (dem/liggghts/run.h).
//
// What the deck contains:
//  - every wall of the scene as `fix mesh/surface` (the belt with `surface_vel`, the pulley with
//    `surface_ang_vel` about its axis, side panels and extra STL walls static) and the plate as
//    `fix mesh/surface/stress` with `reference_point` at the scene's load-cell point;
//  - one atom type per scene material; Young's modulus and Poisson's ratio per type, restitution,
//    sliding and rolling friction per type pair; `model hertz tangential history rolling_friction
//    cdt` for particle-particle and particle-wall contacts;
//  - the feed as `fix insert/stream` from a horizontal face at the bottom of the scene's insertion
//    box, extruded over its height, at the condition's mass flow and the scene's insertion velocity;
//  - the feeder relaxation (feeder_relaxation.h) as `fix addforce` with atom-style variables: the
//    same law, zone and rate, since LIGGGHTS has no such fix;
//  - outputs: the plate's force and torque averaged over each sample interval (`fix ave/time`), a
//    particle dump (id x y z vx vy vz mass) every sample interval downstream of the belt section the
//    sensors read, and the particle count every snapshot (thermo).
// Particles leave the run at the box's faces (`boundary f f f`, lost atoms ignored); the box floor
// is the scene's discharge level.
//
// Not representable, refused with an InputError naming the field: clumps, the linear
// spring-dashpot contact, moving walls, a wall with both a sliding and a turning surface, an
// insertion velocity without a downward component. Body forces in flight and belt adhesion are not
// written (the model that calls this says so in its notes).
#include <map>
#include <string>

#include "core/rig.h"
#include "dem/station/scene.h"
#include "dem/station/settings.h"

namespace chutelab::dem::liggghts {

struct Deck {
  std::string input;                         // the input script
  std::map<std::string, std::string> files;  // relative path -> contents (STL meshes)
  long long steps = 0;                       // time steps run
  long long steps_per_sample = 0;            // plate averages and sensor dumps
  long long samples_per_snapshot = 0;        // snapshot sensors every this many samples
  double dt = 0.0;                           // s
  double dump_x_min = 0.0;                   // m: the dump holds particles with x above this
  // File names the deck writes, relative to its folder.
  static constexpr const char* input_file = "in.station";
  static constexpr const char* plate_file = "plate_load.txt";
  static constexpr const char* dump_file = "particles.dump";
  static constexpr const char* log_file = "log.liggghts";
};

// The deck of a scene. `sim_time` (s) is how long it runs from an empty belt.
Deck make_deck(const Station& st, const station::Scene& sc, const station::RunSettings& s, double sim_time);

// Writes the input and the meshes into `dir` (created).
void write_deck(const Deck& d, const std::string& dir);

}  // namespace chutelab::dem::liggghts
