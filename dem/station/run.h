#pragma once
// One DEM run of a transfer-station condition: build the scene, run until the plate force is
// steady (or the time limit), and reduce the sensors to steady means with standard errors.
#include <functional>
#include <optional>
#include <string>
#include <string_view>
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
inline constexpr const char* kStationModelVersion = "chutelab-dem-station 4";

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
  double restart_time = -1.0;   // s: the simulated time the run continued from (Restart); < 0: from empty
  double transient_end = 0.0;   // s: no window before this (a restart's transit)
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

// Where a restarted run's change first acts (RunOptions::restart): its transient is the time the
// change needs to reach the plate from there, so the steady window is looked for only after it.
enum class ChangeAt {
  plate,   // the particle-plate interaction: only what is on or reaches the plate from now on
  flight,  // forces in flight: the stream released from the pulley from now on
  feed,    // the feed or the belt (flow rate, belt adhesion): the material inserted from now on
};

inline std::string_view name(ChangeAt c) {
  return c == ChangeAt::plate ? "plate" : c == ChangeAt::flight ? "flight" : "feed";
}

// A run that continues a steady run of the same scene at other inputs (issue: restart probes). The
// World's state is the steady run's final one (save_state); the scene is built for this run's
// inputs, so everything that acts from now on is this run's. The change travels from where it acts
// to the plate (`transient`, from the scene: belt transit and flight at belt speed) and the plate
// then settles; the steady window is detected after the transit the way a run from empty detects
// it, and it needs the same length (min_window) as one.
struct Restart {
  std::string from;        // a state written by RunOptions::save_state
  ChangeAt change = ChangeAt::feed;
};

struct RunOptions {
  RunSettings settings;
  DemTable geometry;                 // STL overrides (settings already applied by the caller)
  ExternalInputs external;
  std::function<void(const Progress&)> progress;  // every ~1 % of max_time, and at the end
  std::string vtk_dir;               // "" = no VTK during the run
  double vtk_every = 0.0;            // s between frames of the particle series (0 = only the final state)
  std::size_t side_view_points = 3000;
  // Write the final state here (a World checkpoint), for runs that restart from it. "" = none.
  std::string save_state;
  std::optional<Restart> restart;
};

// Seconds a change acting at `at` needs to reach the plate in this scene, at belt speed: from the
// upstream end of the insertion face along the belt (feed), from the pulley across the flight
// (flight), none (plate); plus one detection block for the plate's layer to follow.
double restart_transit(const Scene& sc, const RunSettings& s, ChangeAt at);

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

// The plate load cell's steady window (steady_state.h) in a series: on R_n alone, the LIGGGHTS rig's
// rule, or, with RunSettings::steady_all_loads, on R_n, R_s and the moment, from where the last of
// them became steady. Not yet checked for length or drift.
SteadyWindow load_cell_window(const StationSeries& series, const RunSettings& s);

// Which plate loads still move through the steady window (judged on R_n alone unless
// RunSettings::steady_all_loads): R_n, R_s and the impact point, each by the early stop's own test
// (WindowTrend::drifting) on its 0.1 s block means, with a note for each. Read from r.forces and
// r.window, so a cached result says the same as the run that made it. A run with no steady window
// (none found, or cut before one could be judged: a short --max-time) names every load.
struct WindowDrift {
  std::string load;  // "R_n", "R_s" or "impact point"
  std::string note;
};
std::vector<WindowDrift> window_drifts(const StationResult& r);

// Writes OUT/timeseries.csv, OUT/sensors.csv, OUT/steady.csv, OUT/trajectory.csv, OUT/side_view.csv,
// OUT/plate_map.csv and OUT/plate_map.vtk.
void write_result_files(const std::string& dir, const StationResult& r);

// A VTK point cloud (ParaView) of the side view, coloured by speed.
void write_side_view_vtk(const std::string& path, const std::vector<SidePoint>& pts);

}  // namespace chutelab::dem::station
