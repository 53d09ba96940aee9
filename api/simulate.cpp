#include "api/simulate.h"

#include <fmt/format.h>

#include "api/effects.h"
#include "api/record_check.h"
#include "core/campaign.h"
#include "core/input_error.h"
#include "core/option_check.h"
#include "core/message.h"
#include "core/rig_needs.h"
#include "dem/station/cache.h"
#include "dem/station/progress.h"
#include "dem/world.h"
#include "effects/registry.h"
#include "validation/dataset.h"
#include "validation/dataset_output.h"
#include "validation/models/dem_model.h"

namespace chutelab::api {
namespace st = dem::station;
namespace {

std::vector<effects::EffectSetting> effect_settings(const SimulateOptions& o) {
  std::vector<effects::EffectSetting> out;
  for (const auto& e : o.effects) out.push_back(effects::parse_setting(e, false));
  return out;
}

}  // namespace

void check(const SimulateOptions& o) {
  if (o.condition.empty()) throw InputError("", 0, "condition", "is empty; give a row of conditions.csv");
  o.settings.check();
  if (o.settings.threads) options::rules::threads.check(static_cast<double>(*o.settings.threads));
  for (const auto& [k, v] : o.settings.wear) {
    st::WearInputs probe;
    st::set_wear(probe, k, v, "", 0, "wear." + k);
  }
  effect_settings(o);
  if (o.vtk_every && !(*o.vtk_every > 0.0)) throw InputError("", 0, "vtk_every", "must be > 0 s");
  if (o.vtk_every && !o.prepare_output) throw InputError("", 0, "vtk_every", "needs " + mention("out") + " DIR");
}

void SimulateResult::write_files(const std::filesystem::path& dir) const {
  st::write_result_files(dir.string(), run);
  st::write_side_view_vtk((dir / "side_view.vtk").string(), run.side_view);
}

SimulateResult simulate(const SimulateOptions& o) {
  namespace fs = std::filesystem;
  check(o);
  SimulateResult res;
  const fs::path dir = o.dataset.empty() ? o.default_dataset : o.dataset;
  const fs::path setup_file = dir / "setup.toml";
  const validation::DatasetFile setup = validation::read_setup_file(setup_file);
  res.setup = validation::read_setup(setup);
  const auto stations = validation::read_conditions(dir / "conditions.csv", res.setup);
  res.station = validation::condition_row(stations, o.condition, dir / "conditions.csv", "condition");
  require_dem_keys(res.station, setup_file.string());
  check_records(o.effects, {}, {res.station});

  const st::DemTable table = st::read_dem_table(setup.shown, &setup.text);
  res.settings = st::resolve(table, o.settings);
  const auto fx = validation::dem_effect_inputs(res.station, effects::instantiate(effect_settings(o)));
  res.effect_notes = fx.notes;

  if (campaign::ranks() > 1)
    throw InputError("", 0, "mpirun",
                     fmt::format("simulate is one DEM run, which does not split over MPI ranks: run it as one process "
                                 "({} for OpenMP); validate, diagnose, sensitivity and calibrate spread their runs over "
                                 "the ranks",
                                 mention("threads")));
  st::RunOptions ro;
  ro.settings = res.settings;
  ro.geometry = table;
  ro.external = fx.external;
  if (o.progress) ro.progress = st::ProgressPrinter(fmt::format("dem {}", res.station.condition));
  if (o.prepare_output) {
    OutputPlan plan;
    plan.inputs = validation::dataset_files(dir);
    for (const auto* s : {&table.stl_plate, &table.stl_belt, &table.stl_pulley})
      if (*s) plan.inputs.emplace_back(**s);
    for (const auto& w : table.stl_walls) plan.inputs.emplace_back(w);
    plan.files = {"timeseries.csv", "sensors.csv", "side_view.vtk"};
    plan.model_folder = true;  // the particle series, vtk/
    if (const fs::path out = o.prepare_output(plan); !out.empty()) {
      ro.vtk_dir = (out / "vtk").string();
      ro.vtk_every = o.vtk_every.value_or(o.default_vtk_every);
    }
  }
  try {
    res.run = st::run_station(fx.station, ro);
  } catch (const dem::SimulationError& e) {
    // Not the fault of one option the user may not have set: said as the run's, with the usual remedy.
    throw InputError("", 0, "simulate",
                     fmt::format("the DEM run failed: {} (a smaller {} may help)", e.what(),
                                 mention(st::field_name(&st::RunSettings::dt_fraction))));
  }
  // Same key as the harness model: a later validate of "dem" with these settings is instant.
  if (o.store_in_cache)
    if (const auto w = st::ResultCache(st::ResultCache::default_dir()).store(validation::dem_cache_key(fx, res.settings, table), res.run);
        !w)
      warn(fmt::format("the run is not cached: {}", w.problem));
  return res;
}

}  // namespace chutelab::api
