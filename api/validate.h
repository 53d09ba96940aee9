#pragma once
// validate: every condition of a dataset through every model, compared with the measurements (ASME
// V&V 20), optionally with the diagnosis and with effects added or fitted. The command line's
// `validate` and the Python package's validate() are this function.
//
//   api::ValidateOptions o;
//   o.dataset = "datasets/grima2010";
//   o.models = {"korzen", "booth-cema"};
//   o.effects = {"air_drag=fit"};
//   api::check(o);                                  // optional: validate() checks first anyway
//   const api::ValidateResult r = api::validate(o);
//   r.final_result().brief();                       // one line; r.files(): the tables and the report
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "api/dem_options.h"
#include "api/output_plan.h"
#include "core/input_error.h"
#include "logs/dataset_logs.h"
#include "reports/report.h"
#include "reports/studies.h"
#include "validation/dataset.h"
#include "validation/diagnosis.h"
#include "validation/harness.h"
#include "validation/output_files.h"
#include "validation/reference_findings.h"
#include "validation/tolerances.h"

namespace chutelab::api {

// A validation's tables and the tolerances judged against, under the library's names: a front end
// reaches them through api/, never through validation/.
using ValidationResult = validation::ValidationResult;
using Tolerances = validation::Tolerances;
using Tolerance = validation::Tolerance;
using validation::model_names;  // every model a models list may name, in registry order

// Errors name the keys "dataset", "models", "effect", "input", "tolerances", "studies", "diagnose",
// "add_missing", "accept_with_effects", "jobs" and the DEM's "dem.*".
//
// The acceptance (tolerances) judges the models as delivered: what they would do with an effect
// added, fitted or fixed, is reported beside it and never decides. accept_with_effects makes the
// models with the effects the ones judged; it takes fixed strengths only (an effect fitted to the
// very measurements it is judged on would pass for the wrong reason), so it excludes add_missing
// and NAME=fit.
struct ValidateOptions {
  std::filesystem::path dataset;                      // folder with measurements
  std::vector<std::string> models{"korzen", "booth-cema"};
  std::vector<std::string> effects;                   // NAME=VALUE or NAME=fit
  std::vector<std::string> inputs;                    // recorded inputs' errors, NAME=VALUE or NAME=fit
  std::filesystem::path tolerances;                   // "" = the dataset's tolerances.toml when present
  bool diagnose = false;                              // also rank the candidate missing effects
  bool add_missing = false;                           // diagnose, then add what it points to, as its verdict states
  bool accept_with_effects = false;                   // the acceptance judges the models with the effects
  // Effects and inputs imply the diagnosis, so that the report shows why they were added.
  bool diagnose_with_effects = true;
  std::vector<std::filesystem::path> studies;         // calibrate / sensitivity output folders or files
  DemOptions dem;
  int jobs = 0;                                       // expensive runs side by side; 0: one per idle core
  bool progress = false;                              // progress lines on stderr (core/progress.h)
  PrepareOutput prepare_output;                       // may be empty (api/output_plan.h)
};

// The options alone, before any file is read. Throws InputError naming the key.
void check(const ValidateOptions& o);

struct ValidateResult {
  validation::Dataset dataset;
  std::optional<validation::Tolerances> tolerances;
  validation::ValidationResult baseline;                 // the models as they are
  std::optional<validation::ValidationResult> with_effects;  // with the effects given or fitted
  std::optional<validation::DiagnosisResult> diagnosis;
  std::vector<reports::EffectDescription> effects;       // what with_effects added
  std::vector<std::string> notes;                        // e.g. the fit's chi^2
  std::vector<validation::ReferenceFinding> findings;    // the reference study's findings checked
  std::vector<reports::StudySection> studies;
  bool added_missing = false;
  // The dataset's logs, when its plate measurements came from them (logs/dataset_logs.h): the
  // report shows each with its window, zero and trend.
  std::optional<logs::LogImport> logs;
  bool accepted_with_effects = false;                    // the options' accept_with_effects

  const validation::ValidationResult& final_result() const { return with_effects ? *with_effects : baseline; }
  // The result the acceptance judges (the exit code, the JUnit file's failures): the models as
  // delivered, or with the effects under accept_with_effects.
  const validation::ValidationResult& accepted() const {
    return accepted_with_effects && with_effects ? *with_effects : baseline;
  }
  // The other one, reported beside the acceptance and never deciding it (null without effects).
  const validation::ValidationResult* beside_acceptance() const {
    if (!with_effects) return nullptr;
    return accepted_with_effects ? &baseline : &*with_effects;
  }
  bool acceptance_failed() const { return accepted().acceptance_failed; }
  // The report's input: views into this result (valid while it lives, unmoved).
  reports::ReportInput report() const;
  // predictions.csv, errors.csv, summary.csv, report.md, report.html, the report's charts as
  // figures/NN-ID.svg (report.md links them) and, with a diagnosis, diagnosis.csv and diagnosis.md.
  std::vector<validation::OutputFile> files() const;
  // The acceptance as JUnit XML (one testcase per checked condition x model x quantity; the other
  // result beside it, all skipped), and what it counted.
  struct JunitCounts {
    int tests = 0, failures = 0, errors = 0, skipped = 0;  // the judged result's
    int beside = 0, beside_outside = 0;  // test cases beside (all skipped), those outside tolerance
  };
  std::string junit(JunitCounts* counts = nullptr) const;
};

// What `validate` prints: the result in a few lines a reader can act on. The counts and RMS E/u_val
// first (one line, before and after an added effect), the quantities the models miss in per cent or
// mm, the diagnosis's verdict, the values outside tolerance as a table, two or three sentences in
// plain words, the acceptance and where the report is (`report_path`). `added_missing`: the effects
// were chosen by add_missing (then "nothing added" is said when the diagnosis found nothing to add).
// Other inputs it names are shown by `names` (a front end's words).
std::string validate_summary(const reports::ReportInput& in, bool added_missing, const std::string& report_path,
                             const FieldNames& names = {});

// check(o), the dataset and every other input read, prepare_output told, then the runs.
ValidateResult validate(const ValidateOptions& o);
// The same on a dataset already read (o.dataset is not used).
ValidateResult validate(validation::Dataset dataset, const ValidateOptions& o);

}  // namespace chutelab::api
