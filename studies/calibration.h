#pragma once
// The slump-test calibration (`chutelab calibrate`, the reference study's Table 3) as data: the sweep's
// files (calibration.csv and its timing, incline.csv), the trends read off the rows, the material
// chosen from them (material.toml), and calibration.csv read back. The pages and the report's section
// that draw it are the report's (reports/calibration_page.h, reports/studies.h).
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "core/rig.h"
#include "dem/rigs/calibration.h"

namespace chutelab::studies {

struct CalibrationContext {
  std::string dataset;   // where the material came from (folder)
  std::string quality;
  Setup setup;           // the dataset's setup (material before calibration); setup.name names the study's rig
};

// "sphere d=5.6mm": the particle of a row, as every output names it.
std::string grain_label(const dem::rigs::CalibrationStudy& s, dem::rigs::GrainKind k);
// The row the material is written from: the closest one, else the first.
const dem::rigs::CalibrationRow& chosen(const dem::rigs::CalibrationStudy& s);
// Plain-language trends of the sweep, computed from the rows (what the reference study's §5 reads off
// Table 3): rolling friction against pile height and bulk density, packing per shape, density.
std::vector<std::string> calibration_findings(const dem::rigs::CalibrationStudy& s);
// "bulk density 1800 kg/m^3, pile height 52.0 mm", or that no target was given.
std::string targets_text(const dem::rigs::CalibrationStudy& s);

// Long form, one slump test a row, with the dataset's name and the quality on every row (the report
// reads it back, read_calibration_csv, and warns when it validates another dataset).
std::string calibration_csv(const CalibrationContext& c, const dem::rigs::CalibrationStudy& s);
// Wall-clock time of each slump test (differs run to run, so it stays out of the study's files).
std::string calibration_timing_csv(const dem::rigs::CalibrationStudy& s);
std::string incline_csv(const dem::rigs::CalibrationStudy& s);
// The dataset's [material] with the chosen solid density and particle-particle rolling friction (the
// first row when no target was given).
std::string material_toml(const CalibrationContext& c, const dem::rigs::CalibrationStudy& s);

// One slump test of a calibration sweep (a row of calibration.csv).
struct CalibrationPoint {
  std::string shape;                 // sphere | clump
  std::string grain;                 // "sphere d=5.6mm"
  double rolling_friction = 0.0;
  double solid_density = 0.0;        // kg/m^3
  double bulk_density = 0.0;         // kg/m^3
  double pile_height = 0.0;          // m
  double repose_angle_deg = 0.0;     // NaN when the flank had too few grains
  long particles = 0;
  bool settled = true;
  double run_seconds = 0.0;
  std::optional<double> distance;    // relative distance to the target
  bool closest = false;
  std::string dataset;               // setup.toml `name` of the calibrated dataset ("" = not recorded)
  std::string quality;               // of the slump tests ("" = not recorded)
};

// Reads calibration.csv (as calibration_csv writes it), with the times of calibration-timing.csv when
// it lies beside it. Throws InputError naming the file, line and column for a missing column, a bad
// number or an empty table.
std::vector<CalibrationPoint> read_calibration_csv(const std::filesystem::path& file);

}  // namespace chutelab::studies
