#pragma once
// diagnose: which physical effect is missing from the models? Ranks the candidate effects by how
// much of the models' misfit to the measurements each explains (validation/diagnosis.h), and can
// check itself on replicas of the dataset's design (validation/self_check.h).
//
//   api::DiagnoseOptions o;
//   o.dataset = "datasets/hidden-effect";
//   const api::DiagnoseResult r = api::diagnose(o);
//   r.diagnosis.verdict;        // one sentence; r.files(): diagnosis.csv, diagnosis.md, ...
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "api/dem_options.h"
#include "api/output_plan.h"
#include "validation/dataset.h"
#include "validation/diagnosis.h"
#include "validation/output_files.h"
#include "validation/self_check.h"

namespace chutelab::api {

// The diagnosis, its self-check and their words under the library's names: a front end reaches
// them through api/, never through validation/.
using DiagnosisResult = validation::DiagnosisResult;
using EffectFit = validation::EffectFit;
using Verdict = validation::Verdict;
using SelfCheckResult = validation::SelfCheckResult;
using validation::diagnosis_markdown;
using validation::self_check_markdown;

// Errors name the keys "dataset", "models", "alpha", "jobs", "self_check", "input" and the DEM's "dem.*".
struct DiagnoseOptions {
  std::filesystem::path dataset;
  std::vector<std::string> models{"booth-cema", "korzen"};  // each measurement: the first that predicts it
  double alpha = 0.01;             // family-wise false-alarm rate over all candidates
  bool pairs = true;               // also fit pairs of effects
  int jobs = 0;                    // expensive runs and fit threads side by side; 0: one per idle core
  // Recorded inputs corrected before the diagnosis, NAME=ERROR (truth minus record) or NAME=fit
  // (fitted first): the candidates are then what the corrected rig still misses.
  std::vector<std::string> inputs;
  int self_check = 0;              // replicas of the design to diagnose too (0: none)
  std::uint64_t seed = 1;          // of the self-check's replicas
  DemOptions dem;
  bool progress = false;           // progress lines on stderr
  PrepareOutput prepare_output;    // may be empty (api/output_plan.h)
};

// The options alone, before any file is read. Throws InputError naming the key.
void check(const DiagnoseOptions& o);

struct DiagnoseResult {
  validation::Dataset dataset;
  validation::DiagnosisResult diagnosis;
  std::vector<std::string> inputs;  // the corrections applied, as "plate_distance=25 (fitted)"
  std::optional<validation::SelfCheckResult> self_check;
  double alpha = 0.01;
  // diagnosis.csv, diagnosis.md (with the self-check appended) and, with a self-check,
  // self_check.md and self_check.csv.
  std::vector<validation::OutputFile> files() const;
};

DiagnoseResult diagnose(const DiagnoseOptions& o);
// The same on a dataset already read (o.dataset is not used).
DiagnoseResult diagnose(validation::Dataset dataset, const DiagnoseOptions& o);

}  // namespace chutelab::api
