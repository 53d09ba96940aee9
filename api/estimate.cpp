#include "api/estimate.h"

#include <array>
#include <cmath>
#include <stdexcept>
#include <fmt/format.h>

#include "analytical/streamline_path.h"
#include "api/design_drawing.h"
#include "api/effects.h"
#include "api/record_check.h"
#include "core/input_error.h"
#include "core/rig.h"
#include "core/units.h"
#include "reports/design.h"
#include "reports/dxf.h"
#include "validation/dataset.h"
#include "validation/harness.h"
#include "validation/models/models.h"

namespace chutelab::api {
namespace {

// The setup keys estimate takes as options: the rig's common geometry and material (core/rig.h's
// ranges and units, mm and kg/m^3).
struct RigOption {
  const std::optional<double>* value;
  std::string_view key;  // RigField::key
  const char* option;    // the neutral key of the option
};
std::array<RigOption, 3> rig_options(const EstimateOptions& o) {
  return {{{&o.pulley_diameter, "pulley_diameter_mm", "pulley_diameter"},
           {&o.belt_width, "belt_width_mm", "belt_width"},
           {&o.bulk_density, "bulk_density_kgm3", "bulk_density"}}};
}
const RigField& field(std::string_view key) {
  for (const auto& f : rig_fields())
    if (f.key == key) return f;
  throw std::logic_error("no rig field " + std::string(key));
}

}  // namespace

void check(const EstimateOptions& o) {
  if (!o.dataset.empty() && !o.setup.empty())
    throw InputError("", 0, "setup", fmt::format("give either {} or {}, not both", mention("dataset"), mention("setup")));
  if (!o.condition.empty() && !o.setup.empty())
    throw InputError("", 0, "condition", fmt::format("{} picks a row of a dataset's conditions.csv; use {}",
                                                     mention("condition"), mention("dataset")));
  // The same bounds as a conditions.csv row (validation::check_operating_input), named by key.
  const std::pair<const std::optional<double>*, std::pair<const char*, const char*>> given[] = {
      {&o.belt_speed, {"belt_speed_mps", "belt_speed"}},
      {&o.mass_flow, {"mass_flow_tph", "mass_flow"}},
      {&o.plate_distance, {"plate_distance_mm", "plate_distance"}},
      {&o.plate_top, {"plate_top_mm", "plate_top"}},
      {&o.stream_thickness, {"stream_thickness_mm", "stream_thickness"}}};
  for (const auto& [value, names] : given)
    if (*value) validation::check_operating_input(names.first, **value, names.second);
  for (const auto& [value, key, option] : rig_options(o)) {
    if (!*value) continue;
    const RigField& f = field(key);
    if (!std::isfinite(**value) || **value < f.min || **value > f.max)
      throw InputError("", 0, option,
                       fmt::format("{} {:g} is outside the physical range [{:g}, {:g}]", f.label, **value, f.min, f.max));
  }
  for (const auto& e : o.effects) effects::parse_setting(e, false);
}

Station resolve_station(const EstimateOptions& o) {
  namespace fs = std::filesystem;
  if (!o.dataset.empty() && !o.setup.empty())
    throw InputError("", 0, "setup", fmt::format("give either {} or {}, not both", mention("dataset"), mention("setup")));
  const validation::Dataset* read = o.dataset_read;
  if (read && !o.setup.empty())
    throw InputError("", 0, "setup", fmt::format("give either {} or {}, not both", mention("dataset"), mention("setup")));
  const fs::path dir = read ? read->dir : o.dataset.empty() ? o.default_dataset : o.dataset;
  const fs::path setup_path = o.setup.empty() ? dir / "setup.toml" : o.setup;
  const Setup setup = read ? read->setup : validation::read_setup(setup_path);

  std::optional<Station> base;
  if (!o.condition.empty()) {
    if (!o.setup.empty())
      throw InputError("", 0, "condition", fmt::format("{} picks a row of a dataset's conditions.csv; use {}",
                                                       mention("condition"), mention("dataset")));
    const validation::DatasetFile* rows = read ? read->source("conditions.csv") : nullptr;
    base = validation::condition_row(read ? read->stations : validation::read_conditions(dir / "conditions.csv", setup),
                                     o.condition, rows ? fs::path(rows->shown) : dir / "conditions.csv", "condition");
  }
  auto need = [&](const std::optional<double>& value, const char* key, double from_base) {
    if (value) return *value;
    if (base) return from_base;
    throw InputError("", 0, key, fmt::format("is required (or pick a dataset row with {})", mention("condition")));
  };
  auto in_bounds = [](double v, const char* column, const char* key) {
    validation::check_operating_input(column, v, key);
    return v;
  };
  // A row's stream_thickness was measured at the row's flow and speed; with another operating
  // point it no longer describes the layer, so h_b comes from continuity unless given.
  const bool operating_point_changed = o.mass_flow || o.belt_speed;
  Station st = validation::make_station(
      setup, base ? base->condition : "cli",
      in_bounds(need(o.belt_speed, "belt_speed", base ? base->belt_speed : 0), "belt_speed_mps", "belt_speed"),
      in_bounds(need(o.mass_flow, "mass_flow", base ? base->mass_flow / units::tph : 0), "mass_flow_tph",
                "mass_flow") * units::tph,
      in_bounds(need(o.plate_distance, "plate_distance", base ? base->plate_distance / units::mm : 0),
                "plate_distance_mm", "plate_distance") * units::mm,
      in_bounds(o.plate_top ? *o.plate_top : base ? base->plate_top / units::mm : 250.0, "plate_top_mm",
                "plate_top") * units::mm,
      o.stream_thickness
          ? std::optional<double>(in_bounds(*o.stream_thickness, "stream_thickness_mm", "stream_thickness") *
                                  units::mm)
          : (base && !operating_point_changed ? base->stream_thickness : std::nullopt));
  if (base) {  // per-condition overrides of the dataset row carry over
    st.belt = base->belt;
    st.plate = base->plate;
    st.material = base->material;
  }
  // The options on top, checked as the setup is (a load wider than its belt, a bulk solid denser
  // than its particles), naming the option.
  for (const auto& [value, key, option] : rig_options(o)) {
    if (!*value) continue;
    const RigField& f = field(key);
    Setup s;
    s.belt = st.belt;
    s.material = st.material;
    f.ref(s) = **value * f.to_si;
    st.belt = s.belt;
    st.material = s.material;
  }
  if (o.belt_width && st.belt.loaded_width > st.belt.belt_width)
    throw InputError("", 0, "belt_width",
                     fmt::format("belt width {:g} mm is narrower than the loaded width {:g} mm of {}", *o.belt_width,
                                 st.belt.loaded_width * 1e3, setup_path.string()));
  if (o.bulk_density && st.material.bulk_density > st.material.solid_density)
    throw InputError("", 0, "bulk_density",
                     fmt::format("bulk density {:g} kg/m^3 is above the solid density {:g} kg/m^3 of {} (a bulk solid "
                                 "has voids)",
                                 *o.bulk_density, st.material.solid_density, setup_path.string()));
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

std::string EstimateResult::svg() const {
  QuantityValues korzen;
  for (const auto& [m, v] : models)
    if (m == "korzen") korzen = v;
  return reports::standalone_svg(reports::design_svg(design_drawing(analysis), korzen));
}

std::vector<Eigen::Vector2d> EstimateResult::path(analytical::Streamline which) const {
  return analytical::streamline_path(analysis, which);
}

std::string EstimateResult::dxf() const { return reports::design_dxf(design_drawing(analysis)); }

EstimateResult estimate(const EstimateOptions& o) {
  check(o);
  const Station st = resolve_station(o);
  check_records(o.effects, {}, {st});
  std::vector<effects::EffectSetting> settings;
  for (const auto& s : o.effects) settings.push_back(effects::parse_setting(s, false));
  EstimatePoint p = estimate_point(st, effects::instantiate(settings));
  return {std::move(p.analysis), std::move(p.models), std::move(settings)};
}

}  // namespace chutelab::api
