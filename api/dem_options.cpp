#include "api/dem_options.h"

#include "core/input_error.h"
#include "core/option_check.h"
#include "dem/station/settings.h"

#include <stdexcept>
#include <vector>

namespace chutelab::api {
namespace {
namespace st = dem::station;

// The field of each setting DemOptions sets, by its member of RunSettings.
const st::DemField& field(DemSetting s) {
  switch (s) {
    case DemSetting::quality: return st::dem_field(&st::RunSettings::quality);
    case DemSetting::steady_on: return st::dem_field(&st::RunSettings::steady_all_loads);
    case DemSetting::plate_cells: return st::dem_field(&st::RunSettings::plate_cells);
  }
  throw std::logic_error("no such DEM setting");
}
constexpr DemSetting kSettings[] = {DemSetting::quality, DemSetting::steady_on, DemSetting::plate_cells};

// A value of a word setting, checked by its field; refused as this command's option `key`.
void check_word(DemSetting s, const std::string& word, const std::string& key) {
  if (const auto p = problem(s, word)) throw InputError("", 0, key, *p);
}
constexpr options::NumberRule kLiggghtsRanks{"dem.liggghts_ranks", 1.0, 1e6, false, false, true, ""};
constexpr options::NumberRule kSimulatedTime{"dem.liggghts_time", 0.0, 100.0, false, false, false, "s"};
}  // namespace

const std::string& key(DemSetting s) {
  static const std::vector<std::string> keys = [] {
    std::vector<std::string> k;
    for (DemSetting x : kSettings) k.push_back("dem." + std::string(field(x).option));
    return k;
  }();
  return keys.at(static_cast<std::size_t>(s));
}

std::vector<std::string> words(DemSetting s) {
  std::vector<std::string> w;
  for (const auto& x : field(s).words()) w.push_back(x.word);
  return w;
}

std::optional<std::string> problem(DemSetting s, const std::string& word) {
  dem::station::DemValue v;
  v.word = word;
  return field(s).problem(v);
}

options::NumberRule rule(DemSetting s) { return field(s).rule(key(s)); }

bool is_dem_setting(std::string_view k) {
  if (st::dem_option(k)) return true;
  for (DemSetting x : kSettings)
    if (key(x) == k) return true;
  return false;
}

void check(const DemOptions& o) {
  if (!o.quality.empty()) check_word(DemSetting::quality, o.quality, key(DemSetting::quality));
  if (!o.signature_quality.empty()) check_word(DemSetting::quality, o.signature_quality, "dem.signature_quality");
  if (!o.steady_on.empty()) check_word(DemSetting::steady_on, o.steady_on, key(DemSetting::steady_on));
  if (o.threads) options::rules::dem_threads.check(static_cast<double>(*o.threads));
  if (o.plate_cells) rule(DemSetting::plate_cells).check(static_cast<double>(*o.plate_cells));
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
  if (!o.quality.empty()) dc.overrides.set(field(DemSetting::quality).option, o.quality);
  dc.overrides.threads = o.threads;
  if (o.plate_cells)
    dc.overrides.set_whole(field(DemSetting::plate_cells).option, static_cast<std::uint64_t>(*o.plate_cells));
  if (!o.steady_on.empty()) dc.overrides.set(field(DemSetting::steady_on).option, o.steady_on);
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
