// `chutelab estimate`: the analytical answer for one condition, in milliseconds, for a designer.
#include <cmath>
#include <fmt/format.h>
#include <tuple>
#include <iostream>
#include <optional>

#include "analytical/impact_zone.h"
#include "analytical/transfer_station.h"
#include "app/commands.h"
#include "api/estimate.h"
#include "app/flag_names.h"
#include "app/sweep.h"
#include "core/input_error.h"
#include "core/output_folder.h"
#include "core/units.h"
#include "effects/registry.h"
#include "reports/design.h"
#include "reports/dxf.h"
#include "validation/dataset.h"
#include "validation/harness.h"
#include "validation/models/models.h"
#include "validation/output_files.h"

namespace chutelab::app {
namespace {

// The estimate's options (api/estimate.h) and what only the command line adds.
struct EstimateCli : api::EstimateOptions {
  std::string format = "table", svg, sweep, dxf, points;
};

// --svg, --dxf, --points FILE: never over a file this run reads, never two flags on one file, and
// all placed together or none (core/output_folder.h).
OutputFolder export_files(const EstimateCli& o) {
  namespace fs = std::filesystem;
  std::vector<fs::path> read = {o.setup};
  if (o.setup.empty()) {
    const fs::path dir = o.dataset.empty() ? o.default_dataset : o.dataset;
    read = {dir / "setup.toml", dir / "conditions.csv"};
  }
  std::vector<fs::path> inputs;
  for (const auto& r : read)
    if (!r.empty()) inputs.push_back(r);
  return OutputFolder(inputs);
}

QuantityValues korzen_reading(const ModelValues& models) {
  for (const auto& [m, v] : models)
    if (m == "korzen") return v;
  return {};
}

int run_sweep(const EstimateCli& o, const analytical::EffectList& fixed,
              const std::vector<effects::EffectSetting>& settings) {
  if (!o.dxf.empty() || !o.points.empty())
    throw InputError("", 0, o.dxf.empty() ? "--points" : "--dxf", "draws one design; leave it out with --sweep");
  const SweepSpec spec = parse_sweep(o.sweep);
  if (spec.kind == SweepSpec::Kind::condition) {
    const bool given = (spec.flag == "--belt-speed" && o.belt_speed) || (spec.flag == "--mass-flow" && o.mass_flow) ||
                       (spec.flag == "--plate-distance" && o.plate_distance) ||
                       (spec.flag == "--plate-top" && o.plate_top) ||
                       (spec.flag == "--stream-thickness" && o.stream_thickness);
    if (given)
      throw InputError("", 0, "--sweep", fmt::format("{} is swept; leave out {}", spec.column, spec.flag));
  }
  if (spec.kind == SweepSpec::Kind::rig)
    for (const auto& [value, column, flag] :
         {std::tuple{&o.pulley_diameter, "pulley_diameter_mm", "--pulley-diameter"},
          std::tuple{&o.belt_width, "belt_width_mm", "--belt-width"},
          std::tuple{&o.bulk_density, "bulk_density_kgm3", "--bulk-density"}})
      if (*value && spec.column == column)
        throw InputError("", 0, "--sweep", fmt::format("{} is swept; leave out {}", spec.column, flag));
  if (spec.kind == SweepSpec::Kind::effect)
    for (const auto& s : settings)
      if (s.info == spec.effect)
        throw InputError("", 0, "--sweep", fmt::format("{} is swept; leave out --effect {}=...", spec.effect->name,
                                                       spec.effect->name));
  std::vector<SweepRow> rows;
  for (double v : spec.values()) {
    EstimateCli at = o;
    if (spec.kind == SweepSpec::Kind::condition) {
      std::optional<double>* slot = spec.flag == "--belt-speed"       ? &at.belt_speed
                                    : spec.flag == "--mass-flow"      ? &at.mass_flow
                                    : spec.flag == "--plate-distance" ? &at.plate_distance
                                    : spec.flag == "--plate-top"      ? &at.plate_top
                                                                      : &at.stream_thickness;
      *slot = v;
    }
    // Inputs that are wrong at every point (a missing flag, a bad file) stop the sweep: exit 2.
    Station st = api::resolve_station(at);
    apply_sweep_value(spec, v, st);
    analytical::EffectList fx = fixed;
    if (spec.kind == SweepSpec::Kind::effect) fx.push_back(spec.effect->make(v));
    SweepRow row{v, std::nullopt, {}, {}, st.plate_top * 1e3,
                 (st.plate_top - st.plate.height * std::cos(st.plate.angle)) * 1e3};
    try {
      // A design with no answer at this point (the stream misses the plate, the load no longer
      // fits the belt) is a result of the sweep, not bad input: the row says why.
      row.point = api::estimate_point(st, fx);
      if (!row.point->analysis.line(analytical::Streamline::korzen_centroid).hit->on_plate)
        row.note = "the centroid meets the plate line off the plate";
      else  // a stream partly over the top edge (or past the foot) loads the plate with less
        row.note = api::stream_miss_note(analytical::impact_zone(row.point->analysis).caught);
    } catch (const InputError& e) {
      row.note = problem_said(e);
      row.why = e.field();
    }
    rows.push_back(std::move(row));
  }
  if (std::none_of(rows.begin(), rows.end(), [](const SweepRow& r) { return r.point.has_value(); }))
    throw InputError("", 0, "--sweep", fmt::format("no point of the sweep has an answer: {}", rows.front().note));
  if (!o.svg.empty()) {
    OutputFolder files = export_files(o);
    files.write_file(o.svg, "--svg", reports::standalone_svg(sweep_chart(spec, rows)));
    files.commit();
  }
  if (o.format == "json")
    std::cout << sweep_json(spec, rows, settings);
  else if (o.format == "csv")
    std::cout << sweep_csv(spec, rows);
  else
    std::cout << sweep_table(spec, rows);
  return kExitOk;
}

int run_estimate(EstimateCli o) {
  o.default_dataset = default_dataset();
  if (!o.sweep.empty()) {
    std::vector<effects::EffectSetting> settings;
    for (const auto& e : o.effects) settings.push_back(effects::parse_setting(e, false));
    return run_sweep(o, effects::instantiate(settings), settings);
  }
  const api::EstimateResult r = api::estimate(o);
  OutputFolder files = export_files(o);
  if (!o.svg.empty())
    files.write_file(o.svg, "--svg", reports::standalone_svg(reports::design_svg(r.analysis, korzen_reading(r.models))));
  if (!o.dxf.empty()) files.write_file(o.dxf, "--dxf", reports::design_dxf(r.analysis));
  if (!o.points.empty()) files.write_file(o.points, "--points", api::streamline_points_csv(r.analysis));
  files.commit();
  std::cout << (o.format == "json" ? r.json() : o.format == "csv" ? r.csv() : r.table());
  return kExitOk;
}

}  // namespace

void add_estimate(CLI::App& app, Action& action) {
  auto o = std::make_shared<EstimateCli>();
  auto* cmd = app.add_subcommand(
      "estimate",
      "Analytical answer (Booth/CEMA + Korzen) for one condition. Without --dataset or --setup the "
      "bundled rig datasets/grima2010 is used.");
  cmd->add_option("--dataset", o->dataset, "dataset folder whose setup.toml (and conditions) to use");
  cmd->add_option("--setup", o->setup, "a setup.toml file");
  cmd->add_option("--condition", o->condition, "start from this row of the dataset's conditions.csv");
  cmd->add_option("--belt-speed", o->belt_speed, "belt speed V_b, m/s");
  cmd->add_option("--mass-flow", o->mass_flow, "mass flow m_s, t/h");
  cmd->add_option("--plate-distance", o->plate_distance, "x of the plate face (top edge), mm");
  cmd->add_option("--plate-top", o->plate_top, "y of the plate's top edge, mm (default 250)");
  cmd->add_option("--stream-thickness", o->stream_thickness,
                  "stream thickness h_b, mm (default: the --condition row's stream_thickness_mm, "
                  "else from continuity; --mass-flow or --belt-speed drops the row's value, so h_b "
                  "then comes from continuity)");
  cmd->add_option("--pulley-diameter", o->pulley_diameter, "head pulley diameter, mm (default: the setup's)");
  cmd->add_option("--belt-width", o->belt_width, "belt width, mm (default: the setup's)");
  cmd->add_option("--bulk-density", o->bulk_density, "bulk density of the load, kg/m^3 (default: the setup's)");
  cmd->add_option("--effect", o->effects, "add a physical effect: NAME=VALUE (repeatable)");
  cmd->add_option("--svg", o->svg,
                  "also draw the design (pulley, streamlines, plate, impact point, Korzen readout) as SVG "
                  "into this file; with --sweep, the chart of impact points and plate forces");
  cmd->add_option("--dxf", o->dxf,
                  "also write the design as ASCII DXF R12 for CAD into this file: mm, origin at the pulley centre; "
                  "layers PULLEY, BELT, PLATE, IMPACT_ZONE and one polyline per streamline (the points_mm of "
                  "--format json)");
  cmd->add_option("--points", o->points,
                  "also write the streamlines' points as CSV into this file (condition, streamline, point, x_mm, "
                  "y_mm; the points_mm of --format json)");
  cmd->add_option("--sweep", o->sweep,
                  "NAME=FROM:TO:STEP: one row per value of an input, the rest held. NAME: belt_speed (m/s), "
                  "mass_flow (t/h), plate_distance, plate_top, stream_thickness (mm), a conditions.csv "
                  "override column (plate_angle_deg, belt_incline_deg, pulley_diameter_mm, friction_plate, ...) "
                  "or an effect name (its strength)");
  cmd->add_option("--format", o->format, "output format")
      ->check(CLI::IsMember({"table", "csv", "json"}));
  cmd->callback([o, &action] { action = [o] { return run_estimate(*o); }; });
}

}  // namespace chutelab::app
