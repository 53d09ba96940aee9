#pragma once
// How the expensive models of validate and diagnose run: the DEM's quality, threads, cache and
// ladder, and LIGGGHTS' launcher. Errors name these by the keys "dem.quality", "dem.threads", ...
// (core/input_error.h), which each front end spells its own way.
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "core/option_check.h"
#include "validation/dataset.h"
#include "validation/models/model_settings.h"

namespace chutelab::api {

struct DemOptions {
  std::string quality;                // "" (the dataset's [dem] table, else quick), quick, standard, paper
  std::optional<int> threads;         // OpenMP threads of a run; unset or 0: one per idle core
  std::string cache;                  // result cache folder; "" = $XDG_CACHE_HOME/chutelab/dem
  bool no_cache = false;              // run again even when the cache holds the result
  bool cache_only = false;            // never run: a run missing from the cache is an error
  bool restart = false;               // runs with effects continue the steady state of the run without
  bool ladder = true;                 // u_num's discretisation part from more runs (validation/gci.h)
  bool ladder_all = false;            // every condition its own time-step ladder, not three carried to all
  std::string signature_quality;      // "" = the predictions' quality
  std::string steady_on;              // "" = the dataset's [dem] steady_on; "normal" (R_n) | "all" (R_n, R_s, moment)
  std::optional<int> plate_cells;     // rows of cells down the generated plate (0: two triangles)
  int liggghts_ranks = 1;             // mpirun -n K liggghts
  std::string liggghts_command;       // "" = mpirun -n K liggghts
  double liggghts_time = 0.0;         // s simulated per LIGGGHTS run; 0 = the quality's maximum
};

// Throws InputError naming the option's key for a value out of its range, before any work.
void check(const DemOptions& o);

// The [dem] settings DemOptions sets, as the front ends offer them: their keys are "dem." + the
// setting's option ("dem.quality": --dem-quality, dem_quality=), their words and ranges those of the
// [dem] table (dem/station/settings.h dem_fields()), which declares each setting once.
enum class DemSetting { quality, steady_on, plate_cells };
const std::string& key(DemSetting s);
// The words setting `s` accepts (quality, steady_on), and why `word` is refused, in the table's
// words (nullopt: accepted).
std::vector<std::string> words(DemSetting s);
std::optional<std::string> problem(DemSetting s, const std::string& word);
// A number setting's range (plate_cells) as the rule of its option key(s).
options::NumberRule rule(DemSetting s);
// Whether `key` is an option of a [dem] setting: one of simulate's (the setting's option,
// "dt_fraction") or of DemOptions (key(DemSetting)).
bool is_dem_setting(std::string_view key);

// The models' settings for a dataset folder (its setup.toml's [dem] table); the DEM's per-condition
// files (series, side views, VTK) go to `output_dir` when it is not empty. Checks `o` first.
// `conditions`: the dataset's, from which the DEM picks the conditions its time-step ladder runs at.
// `setup`: the dataset's setup.toml as read with it (Dataset::sources), when it was.
validation::ModelSettings model_settings(const DemOptions& o, const std::filesystem::path& dataset_dir,
                                         const std::filesystem::path& output_dir, bool progress,
                                         std::span<const Station> conditions = {},
                                         const validation::DatasetFile* setup = nullptr);

// Independent runs side by side in one process: `jobs`, or for 0 one per core other processes
// leave free (the DEM's own thread default).
int resolve_jobs(int jobs);

}  // namespace chutelab::api
