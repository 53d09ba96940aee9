// `chutelab estimate`: the analytical answer for one condition, in milliseconds, for a designer.
#include <iostream>

#include "app/commands.h"
#include "app/estimate.h"
#include "core/input_error.h"

namespace chutelab::app {
namespace {

struct EstimateOptions : EstimateInput {
  std::string format = "table";
};

int run_estimate(EstimateOptions o) {
  o.default_dataset = default_dataset();
  const Estimate e = estimate(o);
  if (o.format == "json")
    std::cout << estimate_json(e.analysis, e.models, e.settings);
  else if (o.format == "csv")
    std::cout << estimate_csv(e.analysis, e.models);
  else
    std::cout << estimate_table(e.analysis, e.models, e.settings);
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
