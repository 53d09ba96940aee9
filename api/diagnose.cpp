#include "api/diagnose.h"

#include <chrono>
#include <fmt/format.h>

#include "api/effects.h"
#include "api/record_check.h"
#include "core/input_error.h"
#include "core/message.h"
#include "core/option_check.h"
#include "core/progress.h"
#include "core/rig_needs.h"
#include "logs/dataset_logs.h"
#include "validation/dataset_output.h"

namespace chutelab::api {
namespace {
constexpr options::NumberRule kJobs{"jobs", 0.0, 256.0, false, false, true, ""};

}  // namespace

void check(const DiagnoseOptions& o) {
  validation::check_model_names(o.models);
  options::rules::alpha.check(o.alpha);
  kJobs.check(static_cast<double>(o.jobs));
  options::rules::self_check.check(static_cast<double>(o.self_check));
  parse_effects(effects_and_inputs({}, o.inputs));
  check(o.dem);
}

std::vector<validation::OutputFile> DiagnoseResult::files() const {
  std::string md = validation::diagnosis_markdown(diagnosis);
  const std::string check_md = self_check ? validation::self_check_markdown(*self_check, alpha) : "";
  if (self_check) md += "\n" + check_md;
  std::vector<validation::OutputFile> out = {{"diagnosis.csv", validation::diagnosis_csv(diagnosis)},
                                             {"diagnosis.md", md}};
  if (self_check) {
    out.emplace_back("self_check.md", check_md);
    out.emplace_back("self_check.csv", validation::self_check_csv(*self_check));
  }
  return out;
}

DiagnoseResult diagnose(const DiagnoseOptions& o) {
  check(o);
  return diagnose(logs::read_dataset(o.dataset, validation::MeasurementsRequired::yes), o);
}

DiagnoseResult diagnose(validation::Dataset dataset, const DiagnoseOptions& o) {
  check(o);
  DiagnoseResult res;
  res.dataset = std::move(dataset);
  res.alpha = o.alpha;
  const validation::Dataset& d = res.dataset;
  if (o.prepare_output) {
    OutputPlan plan;
    plan.inputs = validation::dataset_files(d.dir);
    for (auto& p : model_inputs(o.models)) plan.inputs.push_back(std::move(p));
    plan.files = {"diagnosis.csv", "diagnosis.md", "self_check.md", "self_check.csv"};
    o.prepare_output(plan);
  }
  validation::DiagnoseOptions opt;
  opt.alpha = o.alpha;
  opt.pairs = o.pairs;
  // Resolved once: the free cores may change between two readings. The expensive runs (baseline,
  // signatures, confirmation) go as campaigns with the same number side by side.
  opt.jobs = resolve_jobs(o.jobs);
  // Progress lines are progress: --quiet (or the library's progress=False) leaves them out.
  opt.progress = o.progress && !progress::quiet();
  // An expensive model (the DEM) runs once per condition, and once more per condition for every
  // candidate it can represent (its own signature); the others take the analytical models'
  // signatures, and the winner is confirmed by a real run (DESIGN.md §5, validation/diagnosis.h).
  const auto models = validation::make_models(o.models, model_settings(o.dem, d.dir, {}, o.progress, d.stations, d.source("setup.toml")));
  const auto started = std::chrono::steady_clock::now();
  if (const std::string why = air_drag_unavailable(d.stations); !why.empty()) warn(why);
  if (!o.inputs.empty()) {
    std::vector<validation::ModelPtr> cheap;
    for (const auto& m : models)
      if (!m->expensive()) cheap.push_back(m);
    if (cheap.empty()) throw InputError("", 0, "input", "correcting a record needs an analytical model in " + mention("models"));
    check_records({}, o.inputs, d.stations);
    std::vector<reports::EffectDescription> described;
    const auto applied = resolve_effects(effects_and_inputs({}, o.inputs), d, in_registry_order(cheap), described);
    opt.fixed = applied.effects;
    res.inputs = applied.labels;
  }
  res.diagnosis = validation::diagnose(d, models, opt);
  if (o.self_check > 0) {
    const std::chrono::duration<double> took = std::chrono::steady_clock::now() - started;
    validation::SelfCheckOptions so;
    so.replicas = o.self_check;
    so.seed = o.seed;
    so.diagnose = opt;
    so.diagnose.progress = false;
    so.progress = opt.progress;
    so.seconds_per_diagnosis = took.count();
    res.self_check = validation::self_check(d, res.diagnosis, so);
  }
  return res;
}

}  // namespace chutelab::api
