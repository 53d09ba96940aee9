#pragma once
// A run of one station condition with LIGGGHTS-PUBLIC as the engine: the scene's deck (deck.h) is
// written to a folder and run by an MPI launcher (`mpirun -n K liggghts` by default, or any command
// such as "srun liggghts" on a cluster); its plate series and particle dumps are then measured by
// chutelab's own sensors and steady-state rule (dem/station/sensors.h, steady_state.h,
// run.h reduce_series), so every number means what the built-in DEM's means.
//
// Differences from the built-in DEM's run: LIGGGHTS runs the whole simulated time (no early stop
// once steady); insert/stream moves inserted particles without forces until they cross the feed
// face (the built-in inserter lets them fall from where they are placed); particles leave at the
// box's faces, so `discharged` counts everything that left (`escaped` stays 0); results at
// different rank counts are statistically, not bitwise, equal (domain decomposition changes the
// order of force sums), so the rank count is part of a cached run's key.
#include <functional>
#include <string>

#include "core/rig.h"
#include "dem/liggghts/deck.h"
#include "dem/station/run.h"

namespace chutelab::dem::liggghts {

// Version of chutelab's side of a LIGGGHTS run (deck writer, readers): part of every cache key.
inline constexpr const char* kLiggghtsEngineVersion = "chutelab-liggghts 1";

struct Options {
  station::RunSettings settings;
  station::DemTable geometry;
  station::ExternalInputs external;  // plate friction is honoured (materials); flight and adhesion are not
  int ranks = 1;                     // MPI ranks of the default launcher
  std::string command;               // "" = "mpirun -n <ranks> liggghts"; else the whole launcher + program
  double sim_time = 0.0;             // s simulated; 0 = settings.max_time
  std::string work_dir;              // where the deck runs and its outputs stay (required)
  std::function<void(const station::Progress&)> progress;
  std::size_t side_view_points = 3000;
};

// The launcher + program that runs a deck: options.command, or "mpirun -n K liggghts".
std::string launcher(const Options& o);

// The program of a launcher command (its last word), e.g. "liggghts" of "srun liggghts".
std::string program_of(const std::string& command);

// The first line of `<program> -h` ("LIGGGHTS (Version LIGGGHTS-PUBLIC 3.8.0, ...)"), or "" when
// the program cannot be run.
std::string version(const std::string& program);

// The deck a run of this station would write (for cache keys: its text and meshes are the run).
Deck deck_for(const Station& st, const Options& o);

// Runs the station. Throws InputError when LIGGGHTS is missing, refuses the deck or fails (naming
// the log and LIGGGHTS' error line).
station::StationResult run_station(const Station& st, const Options& o);

// Measures a finished run in `run_dir` (its plate file, dump and log, as the deck of `st` and `o`
// writes them): what run_station does after LIGGGHTS returns, also for a deck run elsewhere, by
// hand or on a cluster.
station::StationResult measure_run(const Station& st, const Options& o, const std::string& run_dir);

}  // namespace chutelab::dem::liggghts
