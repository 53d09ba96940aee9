#pragma once
// One DEM run of a transfer-station condition: build the scene, run until the plate force is
// steady (or the time limit), and reduce the sensors to steady means with standard errors.
#include <functional>
#include <string>
#include <vector>

#include "core/rig.h"
#include "dem/station/plate_map.h"
#include "dem/station/scene.h"
#include "dem/station/sensors.h"
#include "dem/station/settings.h"
#include "dem/station/steady_state.h"

namespace chutelab::dem::station {

// Version of the station model: part of every cache key, bumped whenever a change alters results, so
// that a cached run made by other code is never reused (what each bump changed: `git log -S` on it).
inline constexpr const char* kStationModelVersion = "chutelab-dem-station 3";

struct TrajectoryRow {
  double x = 0.0;  // m
  Estimate upper, lower, centre;  // y, m (mean over steady snapshots; se = sd / sqrt(n))
};

struct StationResult {
  // --- what ran ---
  std::string condition;
  std::string quality;
  double diameter = 0.0;        // m (a clump's spheres)
  std::string shape = "sphere"; // sphere | clump (settings.h ParticleShape)
  double dt = 0.0;              // s
  double collision_time = 0.0;  // s
  double rayleigh_time = 0.0;   // s
  double simulated_time = 0.0;  // s
  long long steps = 0;
  long long rebuilds = 0;       // neighbour-list rebuilds (performance); -1: unknown (an older cache entry)
  double wall_seconds = 0.0;
  bool early_stop = false;
  std::size_t peak_particles = 0;

  // --- steady window of the plate normal force ---
  SteadyWindow window;

  // --- steady means (SI) ---
  Estimate normal_force, shear_force, resultant_force, impact_point_y;
  Estimate impact_velocity, impact_velocity_fast, exit_velocity;
  Estimate layer_speed, layer_height, stream_thickness, mass_flux;
  // x-momentum the stream delivers to the control volume in front of the plate, N (vertical plate:
  // equals R_n in the mean; Sensors::count_crossings).
  Estimate momentum_balance;
  std::vector<TrajectoryRow> trajectory;

  // --- pressure and wear maps (plate_map.h): the plate first, then [dem.stl] walls ---
  std::vector<PlateMap> maps;
  WearInputs wear;  // the wear models' inputs the rates are computed with

  // --- mass at the end, kg ---
  double inserted = 0.0, discharged = 0.0, escaped = 0.0, in_domain = 0.0;

  // --- pictures and series ---
  std::vector<SidePoint> side_view;  // last steady snapshot, subsampled
  double side_view_time = 0.0;
  std::vector<ForceSample> forces;   // plate load cell time series
  std::vector<SnapshotStats> snapshots;  // sensor time series (trajectory arrays dropped when cached)
  std::vector<std::string> notes;
};

struct Progress {
  double time = 0.0;       // simulated, s
  double max_time = 0.0;   // s
  double wall = 0.0;       // s since the start
  std::size_t particles = 0;
  bool done = false;
};

struct RunOptions {
  RunSettings settings;
  DemTable geometry;                 // STL overrides (settings already applied by the caller)
  ExternalInputs external;
  std::function<void(const Progress&)> progress;  // every ~1 % of max_time, and at the end
  std::string vtk_dir;               // "" = no VTK during the run
  double vtk_every = 0.0;            // s between frames of the particle series (0 = only the final state)
  std::size_t side_view_points = 3000;
};

// What a run of any engine recorded: the plate load cell every sample interval (averages over the
// interval ending at t) and the particles near the face at every snapshot (for V_a).
struct StationSeries {
  std::vector<double> t, normal, shear, moment;  // s, N, N, N m
  std::vector<FaceParticle> face;
  double sample_dt = 0.0;  // s
};

// The steady window and every steady mean of `r` (r.forces, r.snapshots and r.simulated_time set)
// from the series, the same way for the built-in DEM and for another code's output.
void reduce_series(const Scene& sc, const Sensors& sensors, const RunSettings& s, const StationSeries& series,
                   StationResult& r);

// Throws InputError for impossible input, dem::SimulationError if the run blows up.
StationResult run_station(const Station& st, const RunOptions& options);

// Writes OUT/timeseries.csv, OUT/sensors.csv, OUT/steady.csv, OUT/trajectory.csv, OUT/side_view.csv,
// OUT/plate_map.csv and OUT/plate_map.vtk.
void write_result_files(const std::string& dir, const StationResult& r);

// A VTK point cloud (ParaView) of the side view, coloured by speed.
void write_side_view_vtk(const std::string& path, const std::vector<SidePoint>& pts);

}  // namespace chutelab::dem::station
