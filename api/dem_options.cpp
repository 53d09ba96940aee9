#include "api/dem_options.h"

#include "core/input_error.h"
#include "core/option_check.h"
#include "dem/station/settings.h"

namespace chutelab::api {
namespace {
// As the [dem] table and dem/station/settings.cpp's check() allow them.
constexpr options::NumberRule kPlateCells{"dem.plate_cells", 0.0, 400.0, false, false, true, ""};
constexpr options::NumberRule kLiggghtsRanks{"dem.liggghts_ranks", 1.0, 1e6, false, false, true, ""};
constexpr options::NumberRule kSimulatedTime{"dem.liggghts_time", 0.0, 100.0, false, false, false, "s"};
}  // namespace

void check(const DemOptions& o) {
  namespace st = dem::station;
  if (!o.quality.empty() && !st::parse_quality(o.quality))
    throw InputError("", 0, "dem.quality", "must be quick, standard or paper");
  if (!o.signature_quality.empty() && !st::parse_quality(o.signature_quality))
    throw InputError("", 0, "dem.signature_quality", "must be quick, standard or paper");
  if (!o.steady_on.empty() && o.steady_on != "normal" && o.steady_on != "all")
    throw InputError("", 0, "dem.steady_on", "must be normal (R_n, the LIGGGHTS rig's rule) or all (R_n, R_s and the moment)");
  if (o.threads) options::rules::dem_threads.check(static_cast<double>(*o.threads));
  if (o.plate_cells) kPlateCells.check(static_cast<double>(*o.plate_cells));
  kLiggghtsRanks.check(static_cast<double>(o.liggghts_ranks));
  kSimulatedTime.check(o.liggghts_time);
  if (o.cache_only && o.no_cache)
    throw InputError("", 0, "dem.cache_only", "contradicts " + mention("dem.no_cache"));
}

// Independent runs side by side scale better than one run's OpenMP threads (no barriers, no shared
// sums: bench/log/STATION.md), so the idle cores go to jobs first; a run alone still gets them all.
int resolve_jobs(int jobs) { return jobs > 0 ? jobs : dem::station::effective_threads(0); }

validation::ModelSettings model_settings(const DemOptions& o, const std::filesystem::path& dataset_dir,
                                         const std::filesystem::path& output_dir, bool progress,
                                         std::span<const Station> conditions, const validation::DatasetFile* setup) {
  check(o);
  validation::DemModelConfig dc;
  dc.setup_file = setup ? setup->shown : (dataset_dir / "setup.toml").string();
  if (setup) dc.setup_text = setup->text;
  if (!o.quality.empty()) dc.overrides.quality = dem::station::parse_quality(o.quality);
  dc.overrides.threads = o.threads;
  dc.overrides.plate_cells = o.plate_cells;
  if (!o.steady_on.empty()) dc.overrides.steady_all_loads = o.steady_on == "all";
  dc.use_cache = !o.no_cache;
  dc.cache_only = o.cache_only;
  dc.ladder = o.ladder;
  dc.ladder_all = o.ladder_all;
  dc.ladder_conditions.assign(conditions.begin(), conditions.end());
  dc.restart = o.restart;
  if (!o.signature_quality.empty()) dc.signature_quality = dem::station::parse_quality(o.signature_quality);
  dc.cache_dir = o.cache;
  dc.progress = progress;
  dc.output_dir = output_dir.string();
  validation::ModelSettings s;
  s.dem = dc;
  s.liggghts.dem = dc;
  s.liggghts.ranks = o.liggghts_ranks;
  s.liggghts.command = o.liggghts_command;
  s.liggghts.sim_time = o.liggghts_time;
  return s;
}

}  // namespace chutelab::api
