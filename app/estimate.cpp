#include "app/estimate.h"

#include <cmath>
#include <fmt/format.h>

#include "core/input_error.h"
#include "core/units.h"
#include "validation/dataset.h"
#include "validation/harness.h"
#include "validation/models/models.h"

namespace chutelab::app {

Station resolve_station(const EstimateInput& o) {
  namespace fs = std::filesystem;
  if (!o.dataset.empty() && !o.setup_file.empty())
    throw InputError("", 0, "--setup", "give either --dataset or --setup, not both");
  const fs::path dir = o.dataset.empty() ? o.default_dataset : fs::path(o.dataset);
  const fs::path setup_path = o.setup_file.empty() ? dir / "setup.toml" : fs::path(o.setup_file);
  const Setup setup = validation::read_setup(setup_path);

  std::optional<Station> base;
  if (!o.condition.empty()) {
    if (!o.setup_file.empty())
      throw InputError("", 0, "--condition", "--condition picks a row of a dataset's conditions.csv; use --dataset");
    base = validation::condition_row(validation::read_conditions(dir / "conditions.csv", setup), o.condition,
                                     dir / "conditions.csv", "--condition");
  }
  auto need = [&](const std::optional<double>& flag, const char* name, double from_base) {
    if (flag) return *flag;
    if (base) return from_base;
    throw InputError("", 0, name, "is required (or pick a dataset row with --condition)");
  };
  // The same bounds as a conditions.csv row (validation::check_operating_input), named by flag.
  auto in_bounds = [](double v, const char* column, const char* flag) {
    validation::check_operating_input(column, v, flag);
    return v;
  };
  // A row's stream_thickness was measured at the row's flow and speed; with another operating
  // point it no longer describes the layer, so h_b comes from continuity unless given.
  const bool operating_point_changed = o.mass_flow || o.belt_speed;
  Station st = validation::make_station(
      setup, base ? base->condition : "cli",
      in_bounds(need(o.belt_speed, "--belt-speed", base ? base->belt_speed : 0), "belt_speed_mps", "--belt-speed"),
      in_bounds(need(o.mass_flow, "--mass-flow", base ? base->mass_flow / units::tph : 0), "mass_flow_tph",
                "--mass-flow") * units::tph,
      in_bounds(need(o.plate_distance, "--plate-distance", base ? base->plate_distance / units::mm : 0),
                "plate_distance_mm", "--plate-distance") * units::mm,
      in_bounds(o.plate_top ? *o.plate_top : base ? base->plate_top / units::mm : 250.0, "plate_top_mm",
                "--plate-top") * units::mm,
      o.stream_thickness
          ? std::optional<double>(in_bounds(*o.stream_thickness, "stream_thickness_mm", "--stream-thickness") *
                                  units::mm)
          : (base && !operating_point_changed ? base->stream_thickness : std::nullopt));
  if (base) {  // per-condition overrides of the dataset row carry over
    st.belt = base->belt;
    st.plate = base->plate;
    st.material = base->material;
  }
  return st;
}

EstimatePoint estimate_point(const Station& st, const analytical::EffectList& fx) {
  EstimatePoint p{analytical::analyse_transfer(st, fx), {}};
  std::vector<validation::ConditionResult> predicted;
  for (const auto& m : validation::analytical_models())
    predicted.push_back({st.condition, m->name(), m->predict(st, fx, {{}, false})});
  validation::apply_measurement_effects(fx, predicted);
  for (const auto& r : predicted) p.models.emplace_back(r.model, r.prediction.values);
  return p;
}

Estimate estimate(const EstimateInput& o) {
  const Station st = resolve_station(o);
  std::vector<effects::EffectSetting> settings;
  for (const auto& s : o.effects) settings.push_back(effects::parse_setting(s, false));
  EstimatePoint p = estimate_point(st, effects::instantiate(settings));
  return {std::move(p.analysis), std::move(p.models), std::move(settings)};
}

}  // namespace chutelab::app
