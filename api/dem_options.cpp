#include "api/dem_options.h"

#include "core/input_error.h"
#include "core/option_check.h"
#include "dem/station/settings.h"

namespace chutelab::api {
namespace {
// The [dem] settings validate and diagnose set (dem/station/settings.h dem_fields()), by their options.
constexpr std::string_view kQuality = "quality", kPlateCells = "plate_cells", kSteadyOn = "steady_on";

// A value of one of them, checked by its field; refused as this command's option `key`.
void check_setting(std::string_view option, const dem::station::DemValue& v, const char* key) {
  if (const auto p = dem::station::dem_option(option)->problem(v)) throw InputError("", 0, key, *p);
}
dem::station::DemValue word(const std::string& w) {
  dem::station::DemValue v;
  v.word = w;
  return v;
}
constexpr options::NumberRule kLiggghtsRanks{"dem.liggghts_ranks", 1.0, 1e6, false, false, true, ""};
constexpr options::NumberRule kSimulatedTime{"dem.liggghts_time", 0.0, 100.0, false, false, false, "s"};
}  // namespace

void check(const DemOptions& o) {
  namespace st = dem::station;
  if (!o.quality.empty()) check_setting(kQuality, word(o.quality), "dem.quality");
  if (!o.signature_quality.empty()) check_setting(kQuality, word(o.signature_quality), "dem.signature_quality");
  if (!o.steady_on.empty()) check_setting(kSteadyOn, word(o.steady_on), "dem.steady_on");
  if (o.threads) options::rules::dem_threads.check(static_cast<double>(*o.threads));
  if (o.plate_cells) st::dem_option(kPlateCells)->rule("dem.plate_cells").check(static_cast<double>(*o.plate_cells));
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
  // validate's --dem-quality, --dem-plate-cells and --dem-steady-on set the [dem] settings of those options.
  if (!o.quality.empty()) dc.overrides.set(kQuality, o.quality);
  dc.overrides.threads = o.threads;
  if (o.plate_cells) dc.overrides.set_whole(kPlateCells, static_cast<std::uint64_t>(*o.plate_cells));
  if (!o.steady_on.empty()) dc.overrides.set(kSteadyOn, o.steady_on);
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
