#pragma once
// calibrate: the reference study's slump-test calibration (§5, Table 3). Sweeps the particle-particle
// rolling friction, the solid density and the particle shape over the swing-arm slump tester
// (dem/rigs), marks the combination closest to the measured bulk density (and pile height), and
// writes it as a [material] block (studies/calibration.h).
//
//   api::CalibrateOptions o;
//   o.dataset = "datasets/grima2010";
//   o.shapes = {"sphere"};
//   o.rolling = {0.15};
//   const api::CalibrateResult r = api::calibrate(o);
//   r.study.closest;            // r.files(): calibration.csv, .md, .html, .svg, material.toml, ...
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "api/output_plan.h"
#include "dem/rigs/calibration.h"
#include "studies/calibration.h"

namespace chutelab::api {

// The study and its words under the library's names: a front end reaches them through api/, never
// through studies/ or dem/ (the house's door, docs/DESIGN.md). A row's grain and motion are said by
// name(), found beside their types.
using CalibrationContext = studies::CalibrationContext;
using CalibrationStudy = dem::rigs::CalibrationStudy;
using studies::grain_label;
using studies::calibration_findings;

// Errors name the keys "dataset", "quality", "rolling", "density", "shape", "sphere_diameter",
// "clump_diameter", "target_bulk_density", "target_pile_height", "threads", "seed" and "jobs".
struct CalibrateOptions {
  std::filesystem::path dataset;           // whose [material] to calibrate; "" = default_dataset
  std::filesystem::path default_dataset;
  std::string quality = "quick";           // quick (~500 spheres, soft) or standard
  std::vector<double> rolling{0.05, 0.1, 0.2};  // particle-particle rolling friction coefficients
  std::vector<double> density{925.0, 1000.0};   // solid densities, kg/m^3
  std::vector<std::string> shapes{"sphere", "clump"};  // sphere (Fig. 4b), clump (2 overlapping spheres, Fig. 4c)
  double sphere_diameter_mm = 5.6, clump_diameter_mm = 4.4;
  bool target = true;                      // false: mark no combination (and write the first one)
  std::optional<double> target_bulk_density;     // kg/m^3; unset: the dataset's bulk_density_kgm3
  std::optional<double> target_pile_height_mm;
  bool incline = true;                     // the inclined-plane rig (particle-wall rolling friction)
  // OpenMP threads per run: a slump test has only a few hundred grains, and threads on a shared
  // 2-core machine spend more time waiting at barriers than computing (measured: 4 s vs 15-100 s).
  int threads = 1;
  std::uint64_t seed = 1;                  // of the pour
  int jobs = 0;                            // runs side by side in this process; 0: one per idle core
  bool progress = false;                   // each slump test's phase on stderr's status line
  // Told what will run (the dataset read, the number of slump tests) once every input is checked and
  // before the first run.
  std::function<void(const studies::CalibrationContext&, int slump_tests)> planned;
  PrepareOutput prepare_output;            // may be empty (api/output_plan.h)
};

// The options alone, before any file is read. Throws InputError naming the key.
void check(const CalibrateOptions& o);

struct CalibrateResult {
  studies::CalibrationContext context;     // the dataset and quality
  dem::rigs::CalibrationStudy study;       // Table 3's rows, the closest, the incline onsets
  // calibration.csv, incline.csv, calibration.md, calibration.html, calibration.svg, material.toml
  // and calibration-timing.csv (the only one with wall-clock times).
  std::vector<OutputFile> files() const;
  std::string table3() const;              // the reference study's layout, Markdown
};

CalibrateResult calibrate(const CalibrateOptions& o);

}  // namespace chutelab::api
