#include "app/flag_names.h"

#include "api/dem_options.h"

#include <algorithm>
#include <array>
#include <utility>


namespace chutelab::app {
namespace {

// Keys whose flag is not "--" + the key with '-' for '_' and '.' (the DEM options of validate and
// diagnose carry a "dem." key; some of their flags put the word elsewhere or drop it).
constexpr auto kRenamed = std::to_array<std::pair<std::string_view, std::string_view>>({
    {"dem.no_cache", "--no-dem-cache"},
    {"dem.signature_quality", "--signature-quality"},
    {"dem.jobs", "--jobs"},
    {"dem.liggghts_ranks", "--liggghts-ranks"},
    {"dem.liggghts_command", "--liggghts-command"},
    {"dem.liggghts_time", "--liggghts-time"},
    {"pairs", "--no-pairs"},
    {"allow_out_of_range", "--allow-out-of-range"},
    {"dem.cache_only", "--dem-cache-only"},
    {"dem.ladder", "--dem-ladder"},
    {"dem.restart", "--dem-restart"},
});

// The options' keys that are spelt by the plain rule besides those of the [dem] settings
// (api::is_dem_setting: simulate's "dt_fraction", validate's "dem.steady_on"). Only these are
// options: a field such as "plate_top_mm" (a column) or "dem.map_cell_mm" (a TOML key) is shown as
// it is. "seed", "quality" and "shape" are also options of synthesize, calibrate and sensitivity.
constexpr auto kPlain = std::to_array<std::string_view>({
    "models", "effect", "input", "dataset", "setup", "condition", "out", "tolerances", "studies", "junit",
    "mapping", "seed", "noise_scale", "noise_factor", "outliers", "alpha", "self_check", "jobs", "threads",
    "dem.threads", "dem.cache", "diagnose", "add_missing", "accept_with_effects", "belt_speed", "mass_flow",
    "plate_distance", "plate_top", "stream_thickness", "pulley_diameter", "belt_width", "bulk_density", "sweep", "svg", "dxf", "points", "format", "quality",
    "shape", "vtk_every", "no_cache", "rolling", "density", "target_bulk_density",
    "target_pile_height", "sizes", "only", "limit", "truth", "sensor", "dem_series"});

// Options whose errors a model run places at the condition it was running (conditions.csv:2): their
// keys are no file's column or TOML key, so they stay flags there.
constexpr auto kLocated = std::to_array<std::string_view>({"models", "effect", "input", "dem.cache_only"});

std::string plain_flag(std::string_view key) {
  std::string f = "--" + std::string(key);
  std::replace(f.begin(), f.end(), '_', '-');
  std::replace(f.begin(), f.end(), '.', '-');
  return f;
}

}  // namespace

std::string flag_for(std::string_view key) {
  for (const auto& [k, flag] : kRenamed)
    if (k == key) return std::string(flag);
  if (std::find(kPlain.begin(), kPlain.end(), key) != kPlain.end() || api::is_dem_setting(key)) return plain_flag(key);
  // simulate's wear inputs, "wear.KEY": one flag per [dem.wear] key (dem/station/settings.h).
  if (key.rfind("wear.", 0) == 0 && key.size() > 5) return plain_flag(key.substr(5));
  return std::string(key);
}

std::string said(const InputError& e) {
  // A field in a file at a line is the file's (a column, a TOML key such as dem.quality), unless it is
  // an option whose error a run placed there.
  const FieldNames field = [&](std::string_view key) {
    const bool option = e.line() == 0 || std::find(kLocated.begin(), kLocated.end(), key) != kLocated.end();
    return option ? flag_for(key) : std::string(key);
  };
  return e.said(field, flag_for);
}

std::string problem_said(const InputError& e) { return e.problem_said(flag_for); }

}  // namespace chutelab::app
