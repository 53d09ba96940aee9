// `chutelab estimate`: the analytical answer for one condition, in milliseconds, for a designer.
#include <cmath>
#include <fmt/format.h>
#include <iostream>
#include <optional>

#include "analytical/transfer_station.h"
#include "app/commands.h"
#include "app/output.h"
#include "core/input_error.h"
#include "core/units.h"
#include "effects/registry.h"
#include "validation/dataset.h"
#include "validation/harness.h"
#include "validation/model.h"

namespace chutelab::app {
namespace {

struct EstimateOptions {
  std::string dataset, setup_file, condition, format = "table";
  std::optional<double> belt_speed, mass_flow, plate_distance, plate_top, stream_thickness;
  std::vector<std::string> effects;
};

Station resolve_station(const EstimateOptions& o) {
  namespace fs = std::filesystem;
  if (!o.dataset.empty() && !o.setup_file.empty())
    throw InputError("", 0, "--setup", "give either --dataset or --setup, not both");
  const fs::path dir = o.dataset.empty() ? default_dataset() : fs::path(o.dataset);
  const fs::path setup_path = o.setup_file.empty() ? dir / "setup.toml" : fs::path(o.setup_file);
  const Setup setup = validation::read_setup(setup_path);

  std::optional<Station> base;
  if (!o.condition.empty()) {
    if (!o.setup_file.empty())
      throw InputError("", 0, "--condition", "--condition picks a row of a dataset's conditions.csv; use --dataset");
    for (const auto& s : validation::read_conditions(dir / "conditions.csv", setup))
      if (s.condition == o.condition) base = s;
    if (!base)
      throw InputError((dir / "conditions.csv").string(), 0, "--condition",
                       fmt::format("no condition named '{}'", o.condition));
  }
  auto need = [&](const std::optional<double>& flag, const char* name, double from_base) {
    if (flag) return *flag;
    if (base) return from_base;
    throw InputError("", 0, name, "is required (or pick a dataset row with --condition)");
  };
  auto positive = [](double v, const char* name) {
    if (!(v > 0.0) || !std::isfinite(v))
      throw InputError("", 0, name, fmt::format("must be a positive number, got {}", v));
    return v;
  };
  // A row's stream_thickness was measured at the row's flow and speed; with another operating
  // point it no longer describes the layer, so h_b comes from continuity unless given.
  const bool operating_point_changed = o.mass_flow || o.belt_speed;
  Station st = validation::make_station(
      setup, base ? base->condition : "cli",
      positive(need(o.belt_speed, "--belt-speed", base ? base->belt_speed : 0), "--belt-speed"),
      positive(need(o.mass_flow, "--mass-flow", base ? base->mass_flow / units::tph : 0),
               "--mass-flow") * units::tph,
      positive(need(o.plate_distance, "--plate-distance", base ? base->plate_distance / units::mm : 0),
               "--plate-distance") * units::mm,
      (o.plate_top ? *o.plate_top : base ? base->plate_top / units::mm : 250.0) * units::mm,
      o.stream_thickness
          ? std::optional<double>(positive(*o.stream_thickness, "--stream-thickness") * units::mm)
          : (base && !operating_point_changed ? base->stream_thickness : std::nullopt));
  if (base) {  // per-condition overrides of the dataset row carry over
    st.belt = base->belt;
    st.plate = base->plate;
    st.material = base->material;
  }
  return st;
}

int run_estimate(const EstimateOptions& o) {
  const Station st = resolve_station(o);
  std::vector<effects::EffectSetting> settings;
  for (const auto& e : o.effects) settings.push_back(effects::parse_setting(e, false));
  const auto fx = effects::instantiate(settings);
  const auto analysis = analytical::analyse_transfer(st, fx);
  std::vector<validation::ConditionResult> predicted;
  for (const auto& m : validation::make_models(validation::model_names()))
    if (!m->expensive()) predicted.push_back({st.condition, m->name(), m->predict(st, fx, {{}, false})});
  validation::apply_measurement_effects(fx, predicted);
  ModelValues models;
  for (const auto& p : predicted) models.emplace_back(p.model, p.prediction.values);
  if (o.format == "json")
    std::cout << estimate_json(analysis, models, settings);
  else if (o.format == "csv")
    std::cout << estimate_csv(analysis, models);
  else
    std::cout << estimate_table(analysis, models, settings);
  return kExitOk;
}

}  // namespace

void add_estimate(CLI::App& app, Action& action) {
  auto o = std::make_shared<EstimateOptions>();
  auto* cmd = app.add_subcommand(
      "estimate",
      "Analytical answer (Booth/CEMA + Korzen) for one condition. Without --dataset or --setup the "
      "bundled rig datasets/grima2010 is used.");
  cmd->add_option("--dataset", o->dataset, "dataset folder whose setup.toml (and conditions) to use");
  cmd->add_option("--setup", o->setup_file, "a setup.toml file");
  cmd->add_option("--condition", o->condition, "start from this row of the dataset's conditions.csv");
  cmd->add_option("--belt-speed", o->belt_speed, "belt speed V_b, m/s");
  cmd->add_option("--mass-flow", o->mass_flow, "mass flow m_s, t/h");
  cmd->add_option("--plate-distance", o->plate_distance, "x of the plate face (top edge), mm");
  cmd->add_option("--plate-top", o->plate_top, "y of the plate's top edge, mm (default 250)");
  cmd->add_option("--stream-thickness", o->stream_thickness,
                  "stream thickness h_b, mm (default: the --condition row's stream_thickness_mm, "
                  "else from continuity; --mass-flow or --belt-speed drops the row's value, so h_b "
                  "then comes from continuity)");
  cmd->add_option("--effect", o->effects, "add a physical effect: NAME=VALUE (repeatable)");
  cmd->add_option("--format", o->format, "output format")
      ->check(CLI::IsMember({"table", "csv", "json"}));
  cmd->callback([o, &action] { action = [o] { return run_estimate(*o); }; });
}

}  // namespace chutelab::app
