#pragma once
// The slump-test calibration (studies/calibration.h) drawn for people: the reference study's Table 3
// layout and the page `chutelab calibrate` writes (Markdown, and HTML with the sweep's chart).
#include <string>

#include "studies/calibration.h"

namespace chutelab::reports {

// The reference study's Table 3 layout: a row per rolling friction x solid density, bulk density and pile height
// per particle shape side by side, the target as the last row (Markdown).
std::string table3_md(const dem::rigs::CalibrationStudy& s);
std::string calibration_md(const studies::CalibrationContext& c, const dem::rigs::CalibrationStudy& s);
std::string calibration_html(const studies::CalibrationContext& c, const dem::rigs::CalibrationStudy& s);
// The page's chart as an SVG file of its own, calibration.svg, which calibration.md links.
std::string calibration_svg(const dem::rigs::CalibrationStudy& s);

}  // namespace chutelab::reports
