// `chutelab diagnose`: which physical effect is missing from the models?
#include <fmt/format.h>
#include <iostream>

#include <algorithm>
#include <thread>

#include "app/commands.h"
#include "core/campaign.h"
#include "app/dem_options.h"
#include "app/option_checks.h"
#include "app/effect_options.h"
#include "core/input_error.h"
#include "core/output_folder.h"
#include "validation/diagnosis.h"
#include "validation/self_check.h"
#include "validation/output_files.h"

namespace chutelab::app {
namespace {

struct DiagnoseCli {
  std::string dataset, out, models = "booth-cema,korzen";
  double alpha = 0.01;
  bool no_pairs = false;
  int jobs = 0;
  int self_check = 0;
  std::uint64_t seed = 1;
  DemCli dem;
};

int run_diagnose(const DiagnoseCli& o) {
  namespace fs = std::filesystem;
  const fs::path dir(o.dataset);
  const auto d = validation::read_dataset(dir);
  auto inputs = dataset_inputs(dir);
  for (auto& p : model_inputs(o.models)) inputs.push_back(std::move(p));
  OutputFolder out(o.out, inputs);
  own_validate_outputs(out);
  check_entries(out, {"diagnosis.csv", "diagnosis.md", "self_check.md", "self_check.csv"});
  const auto names = split_list(o.models);
  validation::DiagnoseOptions opt;
  opt.alpha = o.alpha;
  opt.pairs = !o.no_pairs;
  // Resolved once: the free cores may change between two readings.
  const int jobs = resolve_jobs(o.jobs);
  opt.jobs = jobs;
  opt.progress = true;
  // An expensive model (the DEM) runs once per condition, and once more per condition for every
  // candidate it can represent (its own signature); the others take the analytical models'
  // signatures, and the winner is confirmed by a real run (DESIGN.md §5, validation/diagnosis.h).
  configure_dem_model(o.dem, o.dataset, "");
  // The baseline and confirmation runs go as campaigns (core/campaign.h) with the same --jobs.
  campaign::set_threads(jobs);
  const auto models = validation::make_models(names);
  if (models.empty()) throw InputError("", 0, "--models", "no model given");
  const auto r = validation::diagnose(d, models, opt);
  std::optional<validation::SelfCheckResult> sc;
  if (o.self_check > 0) {
    validation::SelfCheckOptions so;
    so.replicas = o.self_check;
    so.seed = o.seed;
    so.diagnose = opt;
    so.diagnose.progress = false;
    sc = validation::self_check(d, r, so);
  }
  std::string md = validation::diagnosis_markdown(r);
  if (sc) md += "\n" + validation::self_check_markdown(*sc, opt.alpha);
  out.write("diagnosis.csv", validation::diagnosis_csv(r));
  out.write("diagnosis.md", md);
  if (sc) {
    out.write("self_check.md", validation::self_check_markdown(*sc, opt.alpha));
    out.write("self_check.csv", validation::self_check_csv(*sc));
  }
  out.commit();
  std::cout << r.verdict << "\n";
  for (const auto& f : r.findings) std::cout << "- " << f << "\n";
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
  cmd->add_flag("--no-pairs", o->no_pairs, "do not fit pairs of effects");
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
