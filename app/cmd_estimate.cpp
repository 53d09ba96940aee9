// `chutelab estimate`: the analytical answer for one condition, in milliseconds, for a designer.
#include <cmath>
#include <fmt/format.h>
#include <tuple>
#include <iostream>
#include <optional>

#include "app/commands.h"
#include "api/estimate.h"
#include "api/sweep.h"
#include "app/flag_names.h"
#include "core/input_error.h"
#include "core/output_folder.h"

namespace chutelab::app {
namespace {

// The estimate's options (api/estimate.h) and what only the command line adds.
struct EstimateCli : api::SweepOptions {
  std::string format = "table", svg, dxf, points;
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

int run_sweep(const EstimateCli& o) {
  if (!o.dxf.empty() || !o.points.empty())
    throw InputError("", 0, o.dxf.empty() ? "--points" : "--dxf", "draws one design; leave it out with --sweep");
  const api::SweepResult r = api::sweep(o);
  if (!o.svg.empty()) {
    OutputFolder files = export_files(o);
    files.write_file(o.svg, "--svg", r.svg(flag_for));
    files.commit();
  }
  std::cout << (o.format == "json" ? r.json(flag_for) : o.format == "csv" ? r.csv(flag_for) : r.table(flag_for));
  return kExitOk;
}

int run_estimate(EstimateCli o) {
  o.default_dataset = default_dataset();
  if (!o.sweep.empty()) return run_sweep(o);
  const api::EstimateResult r = api::estimate(o);
  OutputFolder files = export_files(o);
  if (!o.svg.empty())
    files.write_file(o.svg, "--svg", r.svg());
  if (!o.dxf.empty()) files.write_file(o.dxf, "--dxf", r.dxf());
  if (!o.points.empty()) files.write_file(o.points, "--points", r.points_csv());
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
