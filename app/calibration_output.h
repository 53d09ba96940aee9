#pragma once
// What `chutelab calibrate` writes: the seed's Table 3 as CSV and Markdown, a self-contained HTML page
// with the sweep drawn, and the chosen material as a [material] block for a dataset's setup.toml.
#include <string>

#include "core/rig.h"
#include "dem/rigs/calibration.h"

namespace chutelab::app {

struct CalibrationContext {
  std::string dataset;   // where the material came from
  std::string quality;
  Setup setup;           // the dataset's setup (material before calibration)
};

std::string calibration_csv(const dem::rigs::CalibrationStudy& s);
std::string incline_csv(const dem::rigs::CalibrationStudy& s);
std::string calibration_md(const CalibrationContext& c, const dem::rigs::CalibrationStudy& s);
std::string calibration_html(const CalibrationContext& c, const dem::rigs::CalibrationStudy& s);
// The dataset's [material] with the chosen solid density and particle-particle rolling friction (the
// first row when no target was given).
std::string material_toml(const CalibrationContext& c, const dem::rigs::CalibrationStudy& s);

}  // namespace chutelab::app
