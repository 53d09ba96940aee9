#pragma once
// Digitised figures in: WebPlotDigitizer's exports turned into dataset rows (DESIGN.md §2).
//
// Inputs (one or more files, one curve per WebPlotDigitizer dataset):
// - its CSV export: x,y column pairs, one pair per dataset side by side; optionally a first row of
//   dataset names (each name over its pair) and/or a row of axis labels ("X,Y"); a shorter
//   dataset leaves its cells empty. A file with one unnamed pair is named after the file (stem).
// - its project JSON: `datasetColl[].name` and `.data[].value = [x, y]` (calibrated data units);
//   a dataset on axes that are not calibrated x-y axes (`axesColl[].type` other than XYAxes,
//   e.g. ImageAxes = pixels) is refused.
//
// The mapping (TOML) says what each curve is; every key is checked, unknown ones are errors:
//   source = "Fig. 7 of ..."              # provenance, copied to the README
//   [defaults]                            # for every curve; each curve may override
//   x_unit = "mm"  y_unit = "mm"          # mm cm m in ft | N kN lbf kgf | m/s ft/s ft/min km/h | t/h kg/s
//   uncertainty = 2.0                     # digitising uncertainty, one sd of y, in y_unit (0 = unknown)
//   uncertainty_px = 2                    # or in pixels, through a project's y calibration; with both,
//                                         # they add in quadrature; a curve stating either
//                                         # replaces both of [defaults]
//   [[curve]]                             # a stream boundary -> trajectory.csv
//   name = "V3-41 upper"  condition = "V3-41"  boundary = "upper"
//   x_offset_mm = 0  y_offset_mm = 0      # the figure's origin in chutelab's frame (pulley centre)
//   [[curve]]                             # a quantity against an operating variable -> measurements.csv
//   name = "R_n 41 t/h"  quantity = "normal_force_N"
//   condition_by = "belt_speed_mps"       # each point is the condition whose value is nearest its x
//   conditions = ["V2-41", "V3-41"]       # candidates (default: every condition)
//   match_tolerance = 0.1                 # in the column's unit (default 5 % of the value)
//   (or condition = "V3-41" for a curve of one point)
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "validation/dataset.h"

namespace chutelab::validation {

struct DigitisedPoint {
  double x = 0.0, y = 0.0;  // the figure's units
  SourceLine where;
  std::string field;        // e.g. "V3-41 upper.y" or "datasetColl[0].data[3].value"
};

// How many y units one pixel is, from a project's axis calibration (CSV exports have none).
struct PixelScale {
  bool log = false;       // log axis: per_px is decades per pixel
  double per_px = 0.0;    // y units (or decades) per pixel along the y axis
  double y_units(double y, double pixels) const;  // the y uncertainty of `pixels` at y
};

struct DigitisedCurve {
  std::string name;
  SourceLine where;
  std::vector<DigitisedPoint> points;
  std::optional<PixelScale> pixel;  // project JSON on calibrated XY axes
};

// By extension: .json is a project file, anything else a CSV export. Throws InputError.
std::vector<DigitisedCurve> read_digitised(const std::filesystem::path& file);

struct DigitisedImport {
  std::vector<Measurement> measurements;    // SI, `where` = the digitised point
  std::vector<TrajectoryPoint> trajectory;  // SI
  std::string source;                       // the mapping's `source`
  std::vector<std::string> summary;         // one line per curve: what it became
  std::vector<std::string> unmapped;        // curves in the inputs that the mapping does not use
};

// Maps the curves onto the dataset's conditions. Every problem throws InputError naming the
// mapping key or the digitised point; rows that the dataset already has are duplicates (errors).
DigitisedImport import_digitised(const Dataset& dataset, const std::filesystem::path& mapping,
                                 const std::vector<DigitisedCurve>& curves);

}  // namespace chutelab::validation
