// `chutelab validate`: every condition through every model, compared with the measurements.
#include <algorithm>
#include <fmt/format.h>
#include <iostream>

#include "app/commands.h"
#include "app/dem_options.h"
#include "app/effect_options.h"
#include "app/validate_console.h"
#include "core/input_error.h"
#include "core/output_folder.h"
#include "core/progress.h"
#include "reports/plain_summary.h"
#include "reports/report.h"
#include "reports/studies.h"
#include "studies/sensitivity.h"
#include "validation/dataset.h"
#include "validation/diagnosis.h"
#include "validation/harness.h"
#include "validation/junit.h"
#include "validation/output_files.h"
#include "validation/tolerances.h"

namespace chutelab::app {
namespace {

struct ValidateCli {
  std::string dataset, out, tolerances, models = "korzen,booth-cema", junit;
  std::vector<std::string> effects;
  bool diagnose = false;
  bool add_missing = false;
  DemCli dem;
  std::vector<std::string> studies;
};

// --junit FILE must not replace a file this run reads or writes elsewhere.
void check_junit_path(const ValidateCli& o, const std::filesystem::path& tolerances_file) {
  namespace fs = std::filesystem;
  if (o.junit.empty()) return;
  const fs::path f(o.junit);
  if (fs::is_directory(f)) throw InputError(o.junit, 0, "--junit", "is a folder; give a file name");
  std::vector<fs::path> taken = {tolerances_file};
  for (const char* n : {"setup.toml", "conditions.csv", "measurements.csv", "trajectory.csv"})
    taken.push_back(fs::path(o.dataset) / n);
  for (const char* n : {"predictions.csv", "errors.csv", "summary.csv", "report.md", "report.html",
                        "diagnosis.csv", "diagnosis.md"})
    taken.push_back(fs::path(o.out) / n);
  const fs::path mine = fs::weakly_canonical(f);
  for (const auto& t : taken)
    if (!t.empty() && fs::weakly_canonical(t) == mine)
      throw InputError(o.junit, 0, "--junit", fmt::format("is {}, which this run reads or writes", t.string()));
}

int run_validate(const ValidateCli& o) {
  namespace fs = std::filesystem;
  const fs::path dir(o.dataset);
  const auto dataset = validation::read_dataset(dir);
  // Read before any model runs: a bad study file ends the command before anything is written.
  const auto studies = reports::read_studies({o.studies.begin(), o.studies.end()}, dataset.setup.name);
  std::optional<chutelab::studies::SensitivityStudy> sensitivity;  // the reference study's finding 6, when one was run
  for (const auto& s : o.studies) {
    const fs::path f = fs::is_directory(s) ? fs::path(s) / "sensitivity.csv" : fs::path(s);
    if (f.filename() == "sensitivity.csv" && fs::exists(f)) sensitivity = chutelab::studies::read_sensitivity_csv(f);
  }
  std::optional<validation::Tolerances> tol;
  if (!o.tolerances.empty()) tol = validation::Tolerances::read(o.tolerances);
  else if (fs::exists(fs::symlink_status(dir / "tolerances.toml"))) tol = validation::Tolerances::read(dir / "tolerances.toml");
  check_junit_path(o, tol ? fs::path(tol->file()) : fs::path());

  // Every file is staged and --out changes only at the end, all at once (core/output_folder.h);
  // checked here, before any model runs, so a bad --out costs no DEM run.
  auto inputs = dataset_inputs(dir);
  if (!o.tolerances.empty()) inputs.emplace_back(o.tolerances);
  for (const auto& s : o.studies) {
    inputs.emplace_back(fs::path(s) / "calibration.csv");
    inputs.emplace_back(fs::path(s) / "sensitivity.csv");
    if (!fs::is_directory(fs::symlink_status(s))) inputs.emplace_back(s);
  }
  for (auto& p : model_inputs(o.models)) inputs.push_back(std::move(p));
  OutputFolder out(o.out, inputs);
  own_validate_outputs(out);
  // "dem" in --models: per-condition series, side views and VTK go under OUT/dem/.
  configure_dem_model(o.dem, o.dataset, (out.staging() / "dem").string());
  const auto models = validation::make_models(split_list(o.models));
  if (models.empty()) throw InputError("", 0, "--models", "no model given");
  check_entries(out, {"predictions.csv", "errors.csv", "summary.csv", "report.md", "report.html"});
  if (o.diagnose || o.add_missing || !o.effects.empty()) check_entries(out, {"diagnosis.csv", "diagnosis.md"});
  if (std::any_of(models.begin(), models.end(), [](const auto& m) { return m->expensive(); }))
    out.check_entry("dem", true);

  validation::ValidateOptions base_opts;
  base_opts.tolerances = tol ? &*tol : nullptr;
  base_opts.quiet = false;
  const auto baseline = validation::validate(dataset, models, base_opts);

  reports::ReportInput report;
  report.dataset = &dataset;
  report.baseline = &baseline;
  auto findings = validation::check_reference_findings(dataset, baseline);
  findings.push_back(chutelab::studies::sensitivity_finding(sensitivity ? &*sensitivity : nullptr, dataset.setup.name));
  report.findings = &findings;
  report.studies = &studies;
  // Fits and the diagnosis call the models hundreds of times: they use the cheap ones (an expensive
  // baseline enters the diagnosis as in DESIGN.md §5, not by re-running it per trial strength).
  std::vector<validation::ModelPtr> cheap;
  for (const auto& m : models)
    if (!m->expensive()) cheap.push_back(m);

  // "What is missing" comes from the models as they are, so the reader sees why an effect was added.
  std::optional<validation::DiagnosisResult> diagnosis;
  if (o.diagnose || o.add_missing || !o.effects.empty()) {
    // Named by the flag that asked for the diagnosis (--effect and --add-missing imply it).
    if (cheap.empty())
      throw InputError("", 0, o.diagnose ? "--diagnose" : o.add_missing ? "--add-missing" : "--effect",
                       "the diagnosis needs an analytical model in --models");
    validation::DiagnoseOptions dopt;
    dopt.progress = true;
    diagnosis = validation::diagnose(dataset, in_registry_order(cheap), dopt);
    report.diagnosis = &*diagnosis;
  }
  // --add-missing: what the diagnosis recommends, fitted (jointly, for a pair).
  std::vector<std::string> effect_args = o.effects;
  if (o.add_missing && diagnosis && diagnosis->best())
    for (const auto& e : diagnosis->best()->effects) effect_args.push_back(e + "=fit");

  const auto applied = resolve_effects(effect_args, dataset, cheap, report.effects);
  std::optional<validation::ValidationResult> after;
  if (!applied.effects.empty()) {
    validation::ValidateOptions opts = base_opts;
    opts.effects = applied.effects;
    opts.effect_labels = applied.labels;
    after = validation::validate(dataset, models, opts);
    report.with_effects = &*after;
  }
  report.notes = applied.notes;
  const auto& final_result = after ? *after : baseline;

  std::vector<validation::OutputFile> files = {
      {"predictions.csv", validation::predictions_csv(final_result)},
      {"errors.csv", validation::errors_csv(final_result)},
      {"summary.csv", validation::summary_csv(final_result)},
      {"report.md", reports::report_markdown(report)},
      {"report.html", reports::report_html(report)}};
  if (diagnosis) {
    files.emplace_back("diagnosis.csv", validation::diagnosis_csv(*diagnosis));
    files.emplace_back("diagnosis.md", validation::diagnosis_markdown(*diagnosis));
  }
  for (const auto& [name, content] : files) out.write(name, content);
  out.commit();
  progress::clear();
  for (const auto& p : final_result.acceptance_problems) std::cerr << "chutelab: acceptance: " << p << "\n";
  validation::JunitSummary junit;
  if (!o.junit.empty()) {  // after the others, under a temporary name first
    const fs::path f(o.junit);
    validation::write_outputs(f.parent_path().empty() ? fs::path(".") : f.parent_path(),
                              {{f.filename().string(),
                                validation::junit_xml(final_result, tol ? &*tol : nullptr, &junit)}});
  }
  std::cout << validate_console(report, o.add_missing, (fs::path(o.out) / "report.html").string());
  if (!o.junit.empty()) {
    std::cout << fmt::format("junit: {} ({} test case{}, {} failed, {} skipped{})\n", o.junit, junit.tests,
                             junit.tests == 1 ? "" : "s", junit.failures, junit.skipped,
                             junit.errors ? fmt::format(", {} error: nothing was checked", junit.errors) : "");
    // The file says so too (an error test case), so a CI view never shows it green; the exit code
    // is the acceptance's own, as without --junit.
    if (junit.nothing_checked())
      std::cerr << "chutelab: --junit: no tolerance applied to any predicted value: nothing was checked "
                   "(the JUnit file reports an error)\n";
  }
  return final_result.acceptance_failed ? kExitAcceptanceFailed : kExitOk;
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
  cmd->add_option("--tolerances", o->tolerances,
                  "acceptance tolerances (default: the dataset's tolerances.toml if present)");
  cmd->add_flag("--diagnose", o->diagnose,
                "also rank the candidate missing effects (always done when --effect is given)");
  cmd->add_flag("--add-missing", o->add_missing,
                "diagnose, then add the effect the measurements point to (fitted) and show the models before and "
                "after")
      ->excludes("--effect");
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
