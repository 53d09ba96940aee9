#include "app/dem_options.h"

#include <filesystem>

#include "app/option_checks.h"
#include "core/campaign.h"
#include "core/input_error.h"
#include "core/progress.h"
#include "dem/station/settings.h"
#include "validation/models/dem_model.h"
#include "validation/models/liggghts_model.h"

namespace chutelab::app {
namespace {
// As the [dem] table and dem/station/settings.cpp's check() allow them.
constexpr options::NumberRule kPlateCells{"", 0.0, 400.0, false, false, true, ""};
constexpr options::NumberRule kSimulatedTime{"", 0.0, 100.0, true, false, false, "s"};
}  // namespace

void add_dem_options(CLI::App& cmd, DemCli& o) {
  cmd.add_option("--dem-quality", o.quality,
                 "DEM quality: quick (default; seconds to minutes per condition), standard (the dataset's "
                 "particles), paper");
  with_rule(cmd.add_option("--dem-threads", o.threads, "OpenMP threads of the DEM (default: one per idle core)"),
            options::rules::dem_threads);
  cmd.add_option("--dem-cache", o.cache, "DEM result cache folder (default $XDG_CACHE_HOME/chutelab/dem)");
  cmd.add_flag("--no-dem-cache", o.no_cache, "run the DEM again even when a cached result exists");
  cmd.add_option("--dem-ladder", o.ladder,
                 "on (default): u_num's discretisation part from more runs per condition: one at twice the time "
                 "step, and two at 1.25 and 1.56 times the particle size when it is coarser than the dataset's (GCI); "
                 "off: statistical part only")
      ->check(CLI::IsMember({"on", "off"}));
  cmd.add_option("--signature-quality", o.signature_quality,
                 "quality of the DEM's own effect-signature runs in diagnose (default: the --dem-quality)")
      ->check(CLI::IsMember({"quick", "standard", "paper"}));
  cmd.add_flag("--dem-cache-only", o.cache_only,
               "never run the DEM: every run must be in the cache (recorded acceptance cases; exit 2 otherwise)");
  with_rule(cmd.add_option("--dem-plate-cells", o.plate_cells,
                           "rows of cells down the generated plate for the DEM's pressure and wear maps (0: two "
                           "triangles)"),
            kPlateCells);
  with_rule(cmd.add_option("--liggghts-ranks", o.liggghts_ranks,
                           "MPI ranks of each LIGGGHTS run (mpirun -n K liggghts; default 1)"),
            options::NumberRule{"", 1.0, 1e6, false, false, true, ""});
  cmd.add_option("--liggghts-command", o.liggghts_command,
                 "launcher and program that run a LIGGGHTS deck, e.g. \"srun liggghts\" (replaces mpirun -n K liggghts)");
  with_rule(cmd.add_option("--liggghts-time", o.liggghts_time,
                           "seconds simulated per LIGGGHTS run (default: the quality's maximum, 1.3 s at standard)"),
            kSimulatedTime);
}

void add_jobs_option(CLI::App& cmd, int& jobs) {
  with_rule(cmd.add_option("--jobs", jobs,
                           "independent DEM runs at a time in this process, each on one thread (under mpirun the "
                           "ranks share the runs instead); default: one per core other processes leave free; "
                           "results do not depend on it"),
            options::rules::jobs);
}

void add_quiet_option(CLI::App& cmd) {
  cmd.add_flag_callback("--quiet", [] { progress::set_quiet(true); },
                        "no progress on stderr (results, warnings and errors still print)");
}

// Independent runs side by side scale better than one run's OpenMP threads (no barriers, no shared
// sums: bench/STATION.md), so the idle cores go to jobs first; a run alone still gets them all.
int resolve_jobs(int jobs) { return jobs > 0 ? jobs : dem::station::effective_threads(0); }

void configure_dem_model(const DemCli& o, const std::string& dataset_dir, const std::string& output_dir) {
  namespace fs = std::filesystem;
  validation::DemModelConfig dc;
  dc.setup_file = (fs::path(dataset_dir) / "setup.toml").string();
  if (!o.quality.empty()) {
    dc.overrides.quality = dem::station::parse_quality(o.quality);
    if (!dc.overrides.quality) throw InputError("", 0, "--dem-quality", "must be quick, standard or paper");
  }
  dc.overrides.threads = o.threads;
  dc.overrides.plate_cells = o.plate_cells;
  dc.use_cache = !o.no_cache;
  dc.cache_only = o.cache_only;
  dc.ladder = o.ladder != "off";
  if (!o.signature_quality.empty()) dc.signature_quality = dem::station::parse_quality(o.signature_quality);
  if (o.cache_only && o.no_cache) throw InputError("", 0, "--dem-cache-only", "contradicts --no-dem-cache");
  dc.cache_dir = o.cache;
  dc.progress = true;
  dc.output_dir = output_dir;
  validation::set_dem_model_config(dc);
  campaign::set_threads(resolve_jobs(o.jobs));
  validation::LiggghtsModelConfig lc;
  lc.dem = dc;
  lc.ranks = o.liggghts_ranks;
  lc.command = o.liggghts_command;
  lc.sim_time = o.liggghts_time;
  validation::set_liggghts_model_config(lc);
}

}  // namespace chutelab::app
