#pragma once
// The DEM flags that validate and diagnose share (--dem-quality, --dem-threads, --dem-cache,
// --no-dem-cache, and --liggghts-ranks, --liggghts-command, --liggghts-time for "liggghts"): both may run "dem" from --models, and a diagnosis after a validate must find
// the validate's runs in the same cache.
#include <filesystem>
#include <optional>
#include <string>

#include <CLI/CLI.hpp>

#include "api/dem_options.h"

namespace chutelab::app {

using api::resolve_jobs;

struct DemCli {
  std::string quality, cache;
  std::optional<int> threads, plate_cells;
  bool no_cache = false;
  bool cache_only = false;
  std::string restart = "off"; // "on" | "off": runs with effects continue the steady state of the run without
  std::string ladder = "on";  // "on" | "all" | "off": the ladders of u_num's discretisation part (dem_options.cpp)
  std::string signature_quality;  // "" = the predictions' quality
  std::string steady_on;          // "" = the dataset's [dem] steady_on; "normal" | "all"
  int jobs = 0;  // DEM runs at a time in one process (core/campaign.h); 0: one per idle core
  int liggghts_ranks = 1;
  std::string liggghts_command;
  double liggghts_time = 0.0;
};

void add_dem_options(CLI::App& cmd, DemCli& o);

// --jobs N: independent DEM runs side by side in one process (each on one thread unless the
// command's thread flag says otherwise); under mpirun the ranks share the runs instead. 0 (the
// default): one per core other processes leave free, as the DEM's own thread default.
void add_jobs_option(CLI::App& cmd, int& jobs);

// --quiet: no progress lines on stderr (core/progress.h); results, warnings and errors still print.
void add_quiet_option(CLI::App& cmd);

// The library's DEM options (api/dem_options.h) as the flags set them.
api::DemOptions dem_options(const DemCli& o);

}  // namespace chutelab::app
