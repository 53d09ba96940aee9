#pragma once
// The transfer-station scene built from one condition of a dataset (a Station): delivery belt (flat
// or troughed) moving at V_b, head pulley turning with it, a feed upstream that drops particles at
// the condition's mass flow into a settling zone, the impact plate (the load cell) with side
// panels, and a sink below. Geometry is generated from the setup; a [dem.stl] table may replace the
// plate, belt or pulley by meshes and add static walls.
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/rig.h"
#include "dem/station/feeder_relaxation.h"
#include "dem/station/flight_force.h"
#include "dem/station/frames.h"
#include "dem/station/settings.h"
#include "dem/world.h"

namespace chutelab::dem::station {

// What added physical effects change in a DEM run beyond the Station (validation/models/dem_model.cpp
// derives them from the harness's effects).
struct ExternalInputs {
  std::optional<double> plate_friction;  // particle-plate sliding friction instead of mu_pw
  double belt_adhesive_stress = 0.0;     // Pa, belt and pulley hold the layer (belt_cohesion.h); 0 = none
  FlightAcceleration flight;             // extra acceleration in flight (air drag)
  std::string flight_key;                // what `flight` is, for cache keys ("" = none)
};

struct Scene {
  std::unique_ptr<World> world;
  BeltFrame belt;
  PlateFrame plate;
  int plate_wall = -1;
  std::vector<int> map_walls;        // [dem.stl] extra walls, mapped like the plate (plate_map.h)
  int inserter = -1;
  int plate_sink = -1;               // the World's sink at the floor (catches what a batch missed)
  std::vector<int> boundary_sinks;   // domain faces: anything there escaped the rig
  double belt_speed = 0.0;           // m/s
  double mass_flow = 0.0;            // kg/s fed
  double diameter = 0.0;             // m, DEM particle diameter (a clump's spheres)
  ParticleShape shape = ParticleShape::sphere;
  double particle_mass = 0.0;        // kg
  double dt = 0.0;                   // s
  double collision_time = 0.0;       // s, shortest Hertz (or LSD) collision at the characteristic speed
  double rayleigh_time = 0.0;        // s
  double characteristic_speed = 0.0; // m/s
  double feed_s_begin = 0.0, feed_s_end = 0.0;  // belt coordinates of the insertion face, m
  double relax_s_end = 0.0;          // belt coordinate where the feeder relaxation ends, m
  double belt_start = 0.0;           // belt coordinate of the belt's upstream end, m
  double sink_y = 0.0;               // m: particles below it have left the rig (the discharge)
  double discharged = 0.0;           // kg removed by discharge()
  // Removes every particle below sink_y in one batch (one neighbour-list rebuild); returns the mass.
  double discharge();
  FeederRelaxation feeder;
  FlightForce flight;
  std::vector<std::string> notes;
  std::shared_ptr<std::vector<std::string>> warnings;  // the World's warnings (first 20)
};

// Builds the scene. Throws InputError for impossible geometry (the plate cutting the pulley,
// particles larger than the load, ...) naming the dataset field.
Scene build_scene(const Station& st, const RunSettings& s, const DemTable& geometry,
                  const ExternalInputs& fx);

}  // namespace chutelab::dem::station
