// `chutelab diagnose`: which physical effect is missing from the models?
#include <fmt/format.h>
#include <iostream>

#include <algorithm>
#include <thread>

#include "api/diagnose.h"
#include "app/commands.h"
#include "app/output_hook.h"
#include "app/dem_options.h"
#include "app/option_checks.h"
#include "app/validate_console.h"
#include "core/input_error.h"
#include "core/output_folder.h"

namespace chutelab::app {
namespace {

struct DiagnoseCli {
  std::string dataset, out, models = "booth-cema,korzen";
  double alpha = 0.01;
  bool no_pairs = false;
  int jobs = 0;
  int self_check = 0;
  std::uint64_t seed = 1;
  std::vector<std::string> inputs;
  DemCli dem;
};

int run_diagnose(const DiagnoseCli& o) {
  namespace fs = std::filesystem;
  api::DiagnoseOptions opt;
  opt.dataset = o.dataset;
  opt.models = split_list(o.models);
  opt.alpha = o.alpha;
  opt.pairs = !o.no_pairs;
  opt.jobs = o.jobs;
  opt.self_check = o.self_check;
  opt.seed = o.seed;
  opt.inputs = o.inputs;
  opt.dem = dem_options(o.dem);
  opt.progress = true;
  std::optional<OutputFolder> out;
  opt.prepare_output = place_output(out, o.out, "diagnose");
  const api::DiagnoseResult res = api::diagnose(opt);
  for (const auto& [name, content] : res.files()) out->write(name, content);
  out->commit();
  const auto& r = res.diagnosis;
  const auto& sc = res.self_check;
  for (const auto& i : res.inputs) std::cout << "corrected record: " << console_text(i) << "\n";
  std::cout << console_text(r.verdict) << "\n";
  for (const auto& f : r.findings) std::cout << "- " << console_text(f) << "\n";
  if (sc) {
    std::cout << fmt::format("self-check ({} replicas of this design): {} false alarm{} among effect-free replicas",
                             sc->null_replicas, sc->false_alarms, sc->false_alarms == 1 ? "" : "s");
    if (!sc->truth.empty())
      std::cout << fmt::format("; with the fitted explanation it was named in {} of {} and its ± 2 sd held the truth "
                               "in {} of {}",
                               sc->named, sc->effect_replicas, sc->covered, sc->effect_replicas);
    std::cout << ".\n";
  }
  std::cout << fmt::format("diagnosis: {}\n", (fs::path(o.out) / "diagnosis.md").string());
  return 0;
}

}  // namespace

void add_diagnose(CLI::App& app, Action& action) {
  auto o = std::make_shared<DiagnoseCli>();
  auto* cmd = app.add_subcommand("diagnose",
                                 "Rank candidate physical effects by how much of the models' misfit "
                                 "to the measurements each explains.");
  cmd->add_option("--dataset", o->dataset, "dataset folder with measurements")->required();
  cmd->add_option("--models", o->models,
                  "comma-separated models; each measurement is compared with the first that predicts it")
      ->capture_default_str();
  with_rule(cmd->add_option("--alpha", o->alpha, "family-wise false-alarm rate over all candidates")
                ->capture_default_str(),
            options::rules::alpha);
  cmd->add_flag("--no-pairs", o->no_pairs, "name one cause at most (do not look for several at once)");
  cmd->add_option("--input", o->inputs,
                  "correct a recorded input before the diagnosis: NAME=ERROR (truth minus record, e.g. "
                  "plate_distance=25 in mm; NAME@CONDITION=ERROR at one condition alone) or NAME=fit; the candidates are then what the corrected rig still misses");
  cmd->add_option("--jobs", o->jobs,
                  "expensive (DEM) runs side by side, and threads of the analytical fits (default: one per core "
                  "other processes leave free; results do not depend on it)")
      ->check(CLI::Range(0, 256));  // 0: the default (one per idle core)
  with_rule(cmd->add_option("--self-check", o->self_check,
                            "also diagnose N replicas of this dataset's design (the analytical models with the "
                            "fitted explanation, or none, plus noise of the stated size): this rig's false-alarm "
                            "rate, power and the coverage of the printed ±"),
            options::rules::self_check);
  with_rule(cmd->add_option("--seed", o->seed, "random seed of the self-check's replicas")->capture_default_str(),
            options::rules::seed);
  add_dem_options(*cmd, o->dem);
  add_quiet_option(*cmd);
  cmd->add_option("--out", o->out, "output folder")->required();
  cmd->callback([o, &action] { action = [o] { return run_diagnose(*o); }; });
}

}  // namespace chutelab::app
