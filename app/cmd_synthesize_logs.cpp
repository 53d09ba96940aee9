// `chutelab synthesize-logs`: the virtual rig, logs written from a known truth through a sensor
// model (api/synthesize_logs.h).
#include <fmt/format.h>
#include <iostream>

#include "api/synthesize_logs.h"
#include "app/commands.h"
#include "app/output_hook.h"
#include "app/option_checks.h"
#include "core/option_check.h"
#include "api/files.h"

namespace chutelab::app {
namespace {

struct SynthesizeLogsCli {
  std::string dataset, truth, sensor, dem_series, out;
  std::uint64_t seed = 1;
};

int run_synthesize_logs(const SynthesizeLogsCli& o) {
  api::SynthesizeLogsOptions opt;
  opt.dataset = o.dataset;
  opt.truth = o.truth;
  opt.sensor = o.sensor;
  opt.dem_series = o.dem_series;
  opt.seed = o.seed;
  opt.prepare_output = check_output(o.out, "synthesize-logs");
  const api::SynthesizeLogsResult r = api::synthesize_logs(opt);
  api::write_dataset(o.out, r.files, r.source.dir, "synthesize-logs");
  std::cout << fmt::format("dataset of logs: {} ({} conditions)\n", o.out, r.truth.size());
  return 0;
}

}  // namespace

void add_synthesize_logs(CLI::App& app, Action& action) {
  auto o = std::make_shared<SynthesizeLogsCli>();
  auto* cmd = app.add_subcommand(
      "synthesize-logs",
      "Write a dataset of rig logs (the virtual rig) from known true means through a sensor model: sampling, "
      "low-pass, noise, quantisation, zero drift, creep, a start-up transient.");
  cmd->add_option("--dataset", o->dataset, "rig, conditions and the measurements no log holds")->required();
  cmd->add_option("--truth", o->truth,
                  "the true means: CSV condition,quantity,value with normal_force_N, shear_force_N, impact_point_y_mm "
                  "(e.g. synthesize --noise-scale 0's measurements.csv, or a model's predictions)")
      ->required();
  cmd->add_option("--sensor", o->sensor, "the sensor model (TOML; default: the built-in one)");
  cmd->add_option("--dem-series", o->dem_series,
                  "folder of DEM runs (<condition>/timeseries.csv): their plate loads' fluctuation rides on the truth");
  with_rule(cmd->add_option("--seed", o->seed, "random seed")->capture_default_str(), options::rules::seed);
  cmd->add_option("--out", o->out, "output folder")->required();
  cmd->callback([o, &action] { action = [o] { return run_synthesize_logs(*o); }; });
}

}  // namespace chutelab::app
