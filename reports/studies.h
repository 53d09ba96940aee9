#pragma once
// Studies run beside a validation — `chutelab calibrate` (reference study Table 3) and `chutelab sensitivity`
// (reference study Table 6) — read back from their output folders and turned into report sections: a verdict or
// finding, a table and a chart. The report draws them like its own sections (report.cpp) and knows
// nothing of how they were made: the CSV files are the interface, and the studies read them
// (studies/calibration.h, studies/sensitivity.h).
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "reports/common.h"
#include "studies/calibration.h"

namespace chutelab::reports {

struct StudySection {
  std::string id;                    // anchor, unique in the page
  std::string title;                 // "Calibration (the reference study's Table 3)"
  std::string verdict;               // highlighted conclusion ("" = none)
  std::vector<std::string> paragraphs;
  Table table;
  std::string chart_svg;             // inline SVG ("" = none)
  std::string caption;
};

struct CalibrationTargetsView {
  std::optional<double> bulk_density;  // kg/m^3
  std::optional<double> pile_height;   // m
};

// Pile height and bulk density against rolling friction, one line per (grain, solid density); the
// targets as dashed lines. Shared by `chutelab calibrate`'s page and the report.
std::string calibration_chart(const std::vector<studies::CalibrationPoint>& points, const CalibrationTargetsView& targets,
                              std::string_view id);

// A section from one CSV file; `suffix` makes its anchors unique when a kind occurs twice. The
// section says which dataset and quality the study used, and warns when that is not `validated` (the
// setup.toml name of the dataset the report is about; "" = do not compare).
StudySection calibration_section(const std::filesystem::path& csv_file, std::string_view suffix = {},
                                 std::string_view validated = {});
StudySection sensitivity_section(const std::filesystem::path& csv_file, std::string_view suffix = {},
                                 std::string_view validated = {});

// "Study on dataset X at Q quality." and, when X is known and not `validated`, a warning that its
// numbers belong to another rig; when X was not recorded, that it cannot be checked.
std::vector<std::string> provenance_paragraphs(std::string_view kind, std::string_view dataset, std::string_view quality,
                                               std::string_view validated);

// Each path is a study folder holding calibration.csv and/or sensitivity.csv, or one of those files.
// Throws InputError when a path is missing or holds neither file, or a file is bad.
std::vector<StudySection> read_studies(const std::vector<std::filesystem::path>& paths, std::string_view validated = {});

}  // namespace chutelab::reports
