#include "api/validate.h"

#include "core/progress.h"

#include <algorithm>
#include <fmt/format.h>

#include "api/effects.h"
#include "api/record_check.h"
#include "api/log_report.h"
#include "core/input_error.h"
#include "core/message.h"
#include "core/option_check.h"
#include "core/rig_needs.h"
#include "effects/registry.h"
#include "reports/report.h"
#include "studies/sensitivity.h"
#include "validation/dataset_output.h"
#include "validation/junit.h"

namespace chutelab::api {
namespace {

constexpr options::NumberRule kJobs{"jobs", 0.0, 256.0, false, false, true, ""};


}  // namespace

void check(const ValidateOptions& o) {
  validation::check_model_names(o.models);
  const auto given = effects_and_inputs(o.effects, o.inputs);
  parse_effects(given);
  if (o.add_missing && !o.effects.empty())
    throw InputError("", 0, "add_missing", "excludes " + mention("effect"));
  if (o.accept_with_effects) {
    if (o.add_missing)
      throw InputError("", 0, "accept_with_effects",
                       "excludes " + mention("add_missing") +
                           ": an effect fitted to the measurements it is judged on passes for the wrong reason; "
                           "give the effect a fixed strength (" + mention("effect") + " NAME=VALUE)");
    if (given.empty())
      throw InputError("", 0, "accept_with_effects",
                       "needs an effect or input with a fixed strength (" + mention("effect") + " NAME=VALUE)");
    if (const auto to_fit = parse_effects(given).to_fit; !to_fit.empty())
      throw InputError("", 0, "accept_with_effects",
                       fmt::format("cannot judge {0}=fit: a strength fitted to the measurements it is judged on "
                                   "passes for the wrong reason; give it a fixed value ({0}=VALUE, e.g. one fitted "
                                   "on other measurements)",
                                   to_fit.front().info->name));
  }
  kJobs.check(static_cast<double>(o.jobs));
  check(o.dem);
}

reports::ReportInput ValidateResult::report() const {
  reports::ReportInput in;
  in.dataset = &dataset;
  in.baseline = &baseline;
  in.with_effects = with_effects ? &*with_effects : nullptr;
  in.effects = effects;
  in.diagnosis = diagnosis ? &*diagnosis : nullptr;
  if (const auto* best = diagnosis ? diagnosis->best() : nullptr)
    for (const auto& nm : best->effects)
      if (const auto* info = effects::find(nm)) in.candidate_physics[nm] = info->physics;
  in.findings = &findings;
  in.notes = notes;
  in.studies = &studies;
  if (logs) {
    in.log_charts = log_charts(*logs);
    in.log_lines = log_lines(*logs);
  }
  in.accepted_with_effects = accepted_with_effects;
  return in;
}

std::vector<validation::OutputFile> ValidateResult::files() const {
  const auto& r = final_result();
  const reports::ReportInput in = report();
  reports::ReportFiles report = reports::report_files(in);
  std::vector<validation::OutputFile> out = {{"predictions.csv", validation::predictions_csv(r)},
                                             {"errors.csv", validation::errors_csv(r)},
                                             {"summary.csv", validation::summary_csv(r)},
                                             {"report.md", std::move(report.markdown)},
                                             {"report.html", std::move(report.html)}};
  for (auto& f : report.figures) out.push_back(std::move(f));
  if (diagnosis) {
    out.emplace_back("diagnosis.csv", validation::diagnosis_csv(*diagnosis));
    out.emplace_back("diagnosis.md", validation::diagnosis_markdown(*diagnosis));
  }
  return out;
}

ValidateResult validate(const ValidateOptions& o) {
  check(o);
  std::optional<logs::LogImport> li;
  validation::Dataset d = logs::read_dataset(o.dataset, validation::MeasurementsRequired::yes, &li);
  ValidateResult r = validate(std::move(d), o);
  r.logs = std::move(li);
  return r;
}

ValidateResult validate(validation::Dataset dataset, const ValidateOptions& o) {
  namespace fs = std::filesystem;
  check(o);
  ValidateResult res;
  res.dataset = std::move(dataset);
  const validation::Dataset& d = res.dataset;
  const fs::path dir = d.dir;
  const std::vector<std::string> given = effects_and_inputs(o.effects, o.inputs);
  // Read before any model runs: a bad study file ends the call before anything is written.
  res.studies = reports::read_studies(o.studies, d.setup.name);
  std::optional<studies::SensitivityStudy> sensitivity;  // the reference study's finding 6, when one was run
  for (const auto& s : o.studies) {
    const fs::path f = fs::is_directory(s) ? s / "sensitivity.csv" : s;
    if (f.filename() == "sensitivity.csv" && fs::exists(f)) sensitivity = studies::read_sensitivity_csv(f);
  }
  // The dataset's own tolerances.toml as it was read with the dataset (its folder may have changed
  // since); one it could not read is read again here, to say why.
  const validation::DatasetFile* own = d.source("tolerances.toml");
  if (!o.tolerances.empty()) res.tolerances = validation::Tolerances::read(o.tolerances);
  else if (own && !own->unread) res.tolerances = validation::Tolerances::read(own->shown, &own->text);
  else if ((own || !d.sources) && !dir.empty() && fs::exists(fs::symlink_status(dir / "tolerances.toml")))
    res.tolerances = validation::Tolerances::read(dir / "tolerances.toml");
  const bool diagnosing = o.diagnose || o.add_missing || (o.diagnose_with_effects && !given.empty());
  check_records(o.effects, o.inputs, d.stations);

  // The models as named (an unknown one is bad input here), then the caller's output folder, then
  // the models again with the folder their per-condition files go to.
  auto models = validation::make_models(o.models, model_settings(o.dem, dir, {}, o.progress, d.stations, d.source("setup.toml")));
  // The diagnosis fits with the analytical models (below): without one, the request is refused here,
  // before any output is prepared or a DEM baseline runs for hours in vain.
  if (diagnosing && std::all_of(models.begin(), models.end(), [](const auto& m) { return m->expensive(); }))
    throw InputError("", 0, o.diagnose ? "diagnose" : o.add_missing ? "add_missing" : o.effects.empty() ? "input" : "effect",
                     "the diagnosis needs an analytical model in " + mention("models"));

  OutputPlan plan;
  plan.inputs = validation::dataset_files(dir);
  if (res.tolerances) plan.inputs.emplace_back(res.tolerances->file());
  for (const auto& s : o.studies) {
    plan.inputs.push_back(s / "calibration.csv");
    plan.inputs.push_back(s / "sensitivity.csv");
    if (!fs::is_directory(fs::symlink_status(s))) plan.inputs.push_back(s);
  }
  for (auto& p : model_inputs(o.models)) plan.inputs.push_back(std::move(p));
  plan.files = {"predictions.csv", "errors.csv", "summary.csv", "report.md", "report.html"};
  plan.folders = {"figures"};
  if (diagnosing) plan.files.insert(plan.files.end(), {"diagnosis.csv", "diagnosis.md"});
  plan.model_folder = std::any_of(models.begin(), models.end(), [](const auto& m) { return m->expensive(); });
  if (o.prepare_output)
    if (const fs::path out = o.prepare_output(plan); !out.empty())
      models = validation::make_models(o.models, model_settings(o.dem, dir, out, o.progress, d.stations, d.source("setup.toml")));

  validation::ValidateOptions base;
  base.tolerances = res.tolerances ? &*res.tolerances : nullptr;
  base.quiet = !o.progress;
  base.jobs = resolve_jobs(o.jobs);
  res.baseline = validation::validate(d, models, base);
  res.findings = validation::check_reference_findings(d, res.baseline);
  res.findings.push_back(studies::sensitivity_finding(sensitivity ? &*sensitivity : nullptr, d.setup.name));

  // Fits and the diagnosis call the models hundreds of times: they use the cheap ones (an expensive
  // baseline enters the diagnosis as in DESIGN.md §5, not by re-running it per trial strength).
  std::vector<validation::ModelPtr> cheap;
  for (const auto& m : models)
    if (!m->expensive()) cheap.push_back(m);
  // "What is missing" comes from the models as they are, so the reader sees why an effect was added.
  if (diagnosing) {
    validation::DiagnoseOptions dopt;
    dopt.progress = o.progress && !progress::quiet();  // --quiet leaves the diagnosis's lines out too
    if (const std::string why = air_drag_unavailable(d.stations); !why.empty()) warn(why);
    res.diagnosis = validation::diagnose(d, in_registry_order(cheap), dopt);
  }
  // add_missing: what the diagnosis recommends, at the strengths its verdict states (its own fit,
  // not a refit of every point as stated, which may go the other way: api/effects.h).
  res.added_missing = o.add_missing;
  res.accepted_with_effects = o.accept_with_effects;
  std::vector<reports::EffectDescription> diagnosed_words;
  AppliedEffects diagnosed;
  if (o.add_missing && res.diagnosis) {
    std::vector<std::string> named;
    for (const auto& a : given) named.push_back(a.substr(0, a.find('=')));
    diagnosed = diagnosed_effects(*res.diagnosis, named, diagnosed_words);
  }
  auto applied = resolve_effects(given, d, cheap, res.effects, diagnosed.effects);
  applied.effects.insert(applied.effects.end(), diagnosed.effects.begin(), diagnosed.effects.end());
  applied.labels.insert(applied.labels.end(), diagnosed.labels.begin(), diagnosed.labels.end());
  applied.notes.insert(applied.notes.end(), diagnosed.notes.begin(), diagnosed.notes.end());
  res.effects.insert(res.effects.end(), diagnosed_words.begin(), diagnosed_words.end());
  if (!applied.effects.empty()) {
    validation::ValidateOptions with = base;
    with.effects = applied.effects;
    with.effect_labels = applied.labels;
    res.with_effects = validation::validate(d, models, with);
  }
  res.notes = applied.notes;
  return res;
}

std::string ValidateResult::junit(JunitCounts* counts) const {
  validation::JunitSummary summary;
  const std::string xml = validation::junit_xml(accepted(), tolerances ? &*tolerances : nullptr, &summary,
                                                beside_acceptance(), accepted_with_effects ? "as-delivered" : "with-effects");
  if (counts) *counts = {summary.tests, summary.failures, summary.errors, summary.skipped, summary.beside,
                         summary.beside_outside};
  return xml;
}

}  // namespace chutelab::api
