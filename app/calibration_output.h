#pragma once
// What `chutelab calibrate` writes: the reference study's Table 3 as CSV and Markdown, a self-contained HTML page
// with the sweep drawn, and the chosen material as a [material] block for a dataset's setup.toml.
#include <string>

#include "core/rig.h"
#include "dem/rigs/calibration.h"

namespace chutelab::app {

struct CalibrationContext {
  std::string dataset;   // where the material came from (folder)
  std::string quality;
  Setup setup;           // the dataset's setup (material before calibration); setup.name names the study's rig
};

// Long form, one slump test a row, with the dataset's name and the quality on every row (the report
// reads it back, reports/studies.h, and warns when it validates another dataset).
// Wall-clock time of each slump test (differs run to run, so it stays out of the study's files).
std::string calibration_timing_csv(const dem::rigs::CalibrationStudy& s);
std::string calibration_csv(const CalibrationContext& c, const dem::rigs::CalibrationStudy& s);
// The reference study's Table 3 layout: a row per rolling friction x solid density, bulk density and pile height
// per particle shape side by side, the target as the last row (Markdown).
std::string table3_md(const dem::rigs::CalibrationStudy& s);
std::string incline_csv(const dem::rigs::CalibrationStudy& s);
std::string calibration_md(const CalibrationContext& c, const dem::rigs::CalibrationStudy& s);
std::string calibration_html(const CalibrationContext& c, const dem::rigs::CalibrationStudy& s);
// The dataset's [material] with the chosen solid density and particle-particle rolling friction (the
// first row when no target was given).
std::string material_toml(const CalibrationContext& c, const dem::rigs::CalibrationStudy& s);

}  // namespace chutelab::app
