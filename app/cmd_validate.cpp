// `chutelab validate`: every condition through every model, compared with the measurements.
#include <algorithm>
#include <fmt/format.h>
#include <iostream>

#include "api/validate.h"
#include "app/commands.h"
#include "app/output_hook.h"
#include "app/dem_options.h"
#include "app/flag_names.h"
#include "app/validate_console.h"
#include "core/input_error.h"
#include "core/output_folder.h"
#include "core/progress.h"

namespace chutelab::app {
namespace {

struct ValidateCli {
  std::string dataset, out, tolerances, models = "korzen,booth-cema", junit;
  std::vector<std::string> effects;
  std::vector<std::string> inputs;
  bool diagnose = false;
  bool add_missing = false;
  bool accept_with_effects = false;
  DemCli dem;
  std::vector<std::string> studies;
};

// --junit FILE must not replace a file this run reads or writes elsewhere.
void check_junit_path(const ValidateCli& o, const api::OutputPlan& plan) {
  namespace fs = std::filesystem;
  if (o.junit.empty()) return;
  const fs::path f(o.junit);
  if (fs::is_directory(f)) throw InputError(o.junit, 0, "--junit", "is a folder; give a file name");
  std::vector<fs::path> taken = plan.inputs;
  for (const auto& n : plan.files) taken.push_back(fs::path(o.out) / n);
  const fs::path mine = fs::weakly_canonical(f);
  for (const auto& t : taken)
    if (!t.empty() && !fs::is_directory(t) && fs::weakly_canonical(t) == mine)
      throw InputError(o.junit, 0, "--junit", fmt::format("is {}, which this run reads or writes", t.string()));
}

int run_validate(const ValidateCli& o) {
  namespace fs = std::filesystem;
  api::ValidateOptions opt;
  opt.dataset = o.dataset;
  opt.models = split_list(o.models);
  opt.effects = o.effects;
  opt.inputs = o.inputs;
  opt.tolerances = o.tolerances;
  opt.diagnose = o.diagnose;
  opt.add_missing = o.add_missing;
  opt.accept_with_effects = o.accept_with_effects;
  opt.studies = {o.studies.begin(), o.studies.end()};
  opt.dem = dem_options(o.dem);
  opt.jobs = o.dem.jobs;
  opt.progress = true;
  // Every file is staged and --out changes only at the end, all at once (core/output_folder.h);
  // placed once every input is read and before any model runs, so a bad --out costs no DEM run.
  std::optional<OutputFolder> out;
  const api::PrepareOutput place = place_output(out, o.out, "validate", [](OutputFolder& f, const api::OutputPlan& plan) {
    if (!plan.model_folder) return fs::path();
    f.check_entry("dem", true);
    // "dem" in --models: per-condition series, side views and VTK go under OUT/dem/.
    return f.staging() / "dem";
  });
  opt.prepare_output = [&o, place](const api::OutputPlan& plan) {
    check_junit_path(o, plan);
    return place(plan);
  };
  const api::ValidateResult r = api::validate(opt);
  // The acceptance judges the models as delivered; the models with effects are reported beside it
  // (api/validate.h, docs/guide-ci.md).
  const auto& judged = r.accepted();
  for (const auto& [name, content] : r.files()) out->write(name, content);
  api::ValidateResult::JunitCounts junit;
  // Placed with --out by the one commit: a --junit that cannot be written leaves --out as it was.
  if (!o.junit.empty()) out->write_file(o.junit, "--junit", r.junit(&junit));
  out->commit();
  progress::clear();
  for (const auto& p : judged.acceptance_problems) std::cerr << "chutelab: acceptance: " << p << "\n";
  std::cout << console_text(
      api::validate_summary(r.report(), o.add_missing, (fs::path(o.out) / "report.html").string(), flag_for));
  if (!o.junit.empty()) {
    std::cout << fmt::format("junit: {} ({} test case{}, {} failed, {} skipped{}{})\n", o.junit, junit.tests,
                             junit.tests == 1 ? "" : "s", junit.failures, junit.skipped,
                             junit.errors ? fmt::format(", {} error: nothing was checked", junit.errors) : "",
                             junit.beside ? fmt::format("; {} more beside, {}, not judged (skipped), {} of them "
                                                        "outside tolerance",
                                                        junit.beside,
                                                        r.accepted_with_effects ? "the models as delivered"
                                                                                : "the models with the effects",
                                                        junit.beside_outside)
                                          : "");
    // The file says so too (an error test case), so a CI view never shows it green; the exit code
    // is the acceptance's own, as without --junit.
    if (junit.errors > 0)
      std::cerr << "chutelab: --junit: no tolerance applied to any predicted value: nothing was checked "
                   "(the JUnit file reports an error)\n";
  }
  return r.acceptance_failed() ? kExitAcceptanceFailed : kExitOk;
}

}  // namespace

void add_validate(CLI::App& app, Action& action) {
  auto o = std::make_shared<ValidateCli>();
  auto* cmd = app.add_subcommand("validate",
                                 "Run every condition of a dataset through the models and compare "
                                 "with its measurements; writes CSV tables and a report.");
  cmd->add_option("--dataset", o->dataset, "dataset folder with measurements")->required();
  cmd->add_option("--models", o->models, "comma-separated models")->capture_default_str();
  cmd->add_option("--effect", o->effects,
                  "add a physical effect: NAME=VALUE or NAME=fit (calibrated on the dataset)");
  cmd->add_option("--input", o->inputs,
                  "correct a recorded input: NAME=ERROR (truth minus record, e.g. plate_distance=25 in mm; "
                  "NAME@CONDITION=ERROR at one condition alone) or NAME=fit");
  cmd->add_option("--tolerances", o->tolerances,
                  "acceptance tolerances (default: the dataset's tolerances.toml if present)");
  cmd->add_flag("--diagnose", o->diagnose,
                "also rank the candidate missing effects (always done when --effect is given)");
  cmd->add_flag("--add-missing", o->add_missing,
                "diagnose, then add the effect the measurements point to (fitted) and show the models before and "
                "after")
      ->excludes("--effect");
  cmd->add_flag("--accept-with-effects", o->accept_with_effects,
                "judge the acceptance (exit code, --junit) on the models with the effects given, which then need "
                "fixed strengths (NAME=VALUE); without it the models as delivered are judged and the models with "
                "effects reported beside");
  add_dem_options(*cmd, o->dem);
  add_jobs_option(*cmd, o->dem.jobs);
  add_quiet_option(*cmd);
  cmd->add_option("--studies", o->studies,
                  "folders of `chutelab calibrate` / `sensitivity` runs (comma list or repeated): their tables "
                  "and charts become report sections")
      ->delimiter(',');
  cmd->add_option("--junit", o->junit,
                  "also write the acceptance results as JUnit XML (one test case per condition x model x "
                  "quantity with a tolerance; an error test case when nothing was checked)");
  cmd->add_option("--out", o->out, "output folder")->required();
  cmd->callback([o, &action] { action = [o] { return run_validate(*o); }; });
}

}  // namespace chutelab::app
