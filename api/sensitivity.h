#pragma once
// sensitivity: the reference study's Table 6 (§6.1) at one condition. The transfer-station DEM runs
// once per variant (LSD vs Hertz-Mindlin, sphere vs two-sphere clump, dt/20, G x10 and /10, the
// reference study's particle sizes) as one campaign, and the study (studies/sensitivity.h) says
// whether the reference study's conclusion is reproduced.
//
//   api::SensitivityOptions o;
//   o.dataset = "datasets/grima2010";
//   o.only = {"G/10"};
//   const api::SensitivityResult r = api::sensitivity(o);
//   r.study.verdict.text;       // r.files(): sensitivity.csv, .md, .html, .svg, sensitivity-timing.csv
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "api/output_plan.h"
#include "studies/sensitivity.h"

namespace chutelab::api {

// The study and its words under the library's names: a front end reaches them through api/, never
// through studies/ (the house's door, docs/DESIGN.md). A variant's group is said by name(), found
// beside its type.
using SensitivityStudy = studies::SensitivityStudy;
using SensitivityVariant = studies::SensitivityVariant;
using studies::variant_columns;
using studies::run_notes;

// Errors name the keys "dataset", "condition", "quality", "only", "sizes", "limit", "threads",
// "seed" and "jobs".
struct SensitivityOptions {
  std::filesystem::path dataset;           // "" = default_dataset
  std::filesystem::path default_dataset;
  std::string condition = "V3-41";         // reference study Table 6: V_b = 3 m/s, 41 t/h
  std::string quality = "quick";           // the base run's preset: quick, standard or paper
  std::vector<std::string> only;           // run only these variants besides the base (keys); empty: all
  // Sphere diameters of the size variants, mm (the one equal to the base diameter is the base).
  // Empty: the reference study's 5.6, 9 and 13.6 mm; at quick quality 9 and 13.6 (a 5.6 mm run alone
  // would break the ~10 min budget; the verdict then says so).
  std::vector<double> sizes_mm;
  // OpenMP threads per run. Unset: 1 (on a shared 2-core machine a second thread made runs slower,
  // bench/log/STATION.md); results do not depend on it.
  std::optional<int> threads;
  std::optional<std::uint64_t> seed;       // the feed's; unset: the dataset's
  double limit = 10.0;                     // "changes little": |change of mean R| <= this, %
  int jobs = 0;                            // runs side by side in this process; 0: one per idle core
  bool progress = false;                   // progress on stderr: each run's bar, a line per finished run
  // Told the study as planned (its base, notes and what is left out; no rows yet) and the variants
  // to run, once every input is checked and before the first run.
  std::function<void(const studies::SensitivityStudy&, const std::vector<studies::SensitivityVariant>&)> planned;
  PrepareOutput prepare_output;            // may be empty (api/output_plan.h)
};

// The options alone, before any file is read. Throws InputError naming the key.
void check(const SensitivityOptions& o);

struct SensitivityResult {
  studies::SensitivityStudy study;         // rows[0] is the base; the verdict is evaluated
  // sensitivity.csv, sensitivity.md, sensitivity.html, sensitivity.svg and sensitivity-timing.csv
  // (the only one with wall-clock times).
  std::vector<OutputFile> files() const;
};

SensitivityResult sensitivity(const SensitivityOptions& o);

}  // namespace chutelab::api
