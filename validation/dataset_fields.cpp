#include "validation/dataset_fields.h"

#include <array>
#include <fmt/format.h>

#include "core/units.h"

namespace chutelab::validation {
namespace {

constexpr std::array<ColumnSpec, 6> kConditions = {{
    {"condition", true, "", "the condition's name, unique in the file; the other files refer to it", "V2-26"},
    {"belt_speed_mps", true, "m/s", "belt speed V_b", "2.0"},
    {"mass_flow_tph", true, "t/h", "mass flow m_s on the belt", "26.0"},
    {"plate_distance_mm", true, "mm",
     "x of the plate face at its top edge, from the pulley centre (the reference study's Z)", "300.0"},
    {"plate_top_mm", true, "mm", "y of the plate's top edge, above the pulley centre", "250.0"},
    {"stream_thickness_mm", false, "mm",
     "measured stream thickness h_b; an empty cell or no column: from continuity (mass flow, bulk density, belt "
     "speed and the load's shape)",
     ""},
}};

// span: check_operating_input's range of each input, the widest uncertainty that still leaves a rig.
constexpr std::array<UncertaintyColumn, 5> kOperating = {{
    {"belt_speed_uncertainty_mps", "belt_speed_mps", "m/s", 1.0, &InputUncertainties::belt_speed, 50.0},
    {"mass_flow_uncertainty_tph", "mass_flow_tph", "t/h", units::tph, &InputUncertainties::mass_flow, 1e5},
    {"plate_distance_uncertainty_mm", "plate_distance_mm", "mm", units::mm, &InputUncertainties::plate_distance, 1e5},
    {"plate_top_uncertainty_mm", "plate_top_mm", "mm", units::mm, &InputUncertainties::plate_top, 2e5},
    {"stream_thickness_uncertainty_mm", "stream_thickness_mm", "mm", units::mm,
     &InputUncertainties::stream_thickness, 1e4},
}};

constexpr std::array<ColumnSpec, 4> kMeasurements = {{
    {"condition", true, "", "a condition of conditions.csv", "V2-26"},
    {"quantity", true, "", "what was measured: one of the quantities below", "normal_force_N"},
    {"value", true, "the quantity's", "the measured mean, in the unit the quantity's name ends with", "14.9"},
    {"uncertainty", false, "the quantity's",
     "one standard deviation of the value; an empty cell, 0 or no column: unknown, the value is left out of "
     "E/u_val and the statistics, with a warning",
     "0.30"},
}};

constexpr std::array<ColumnSpec, 5> kTrajectory = {{
    {"condition", true, "", "a condition of conditions.csv", "V2-26"},
    {"boundary", true, "", "which edge of the stream: upper, lower or centre", "upper"},
    {"x_mm", true, "mm", "horizontal distance from the pulley centre, between the pulley and the plate face",
     "100.0"},
    {"y_mm", true, "mm", "height of the stream's edge at x, above the pulley centre", "169.4"},
    {"uncertainty_mm", false, "mm", "one standard deviation of y; empty, 0 or no column: unknown, with a warning",
     "2.0"},
}};

constexpr std::array<ColumnSpec, 6> kPlateMap = {{
    {"condition", true, "", "a condition of conditions.csv", "V2-26"},
    {"y_mm", true, "mm", "height of the point on the plate face, above the pulley centre (a point off the face is refused)", "100.0"},
    {"z_mm", true, "mm", "lateral position of the point (0: the belt's centre line; within half the plate width)", "0.0"},
    {"quantity", true, "", "what was measured: one of the plate quantities below", "plate_pressure_Pa"},
    {"value", true, "the quantity's", "the measured value, in the unit the quantity's name ends with", "4200"},
    {"uncertainty", false, "the quantity's", "one standard deviation; empty, 0 or no column: unknown, with a warning",
     "400"},
}};

constexpr std::array<ColumnSpec, 2> kSetupTexts = {{
    {"name", false, "", "the rig's name, in titles", "my-rig"},
    {"source", false, "", "where the numbers come from, in the report's provenance", "our rig, 2026 campaign"},
}};

}  // namespace

std::span<const ColumnSpec> condition_columns() { return kConditions; }
std::span<const UncertaintyColumn> operating_uncertainty_columns() { return kOperating; }
std::span<const ColumnSpec> measurement_columns() { return kMeasurements; }
std::span<const ColumnSpec> trajectory_columns() { return kTrajectory; }
std::span<const ColumnSpec> plate_map_columns() { return kPlateMap; }
std::span<const ColumnSpec> setup_texts() { return kSetupTexts; }

std::vector<std::string_view> required_columns(std::span<const ColumnSpec> columns) {
  std::vector<std::string_view> out;
  for (const auto& c : columns)
    if (c.required) out.push_back(c.name);
  return out;
}

std::string layout_of(std::span<const ColumnSpec> columns) {
  std::vector<std::string_view> names, example;
  for (const auto& c : columns) {
    names.push_back(c.name);
    example.push_back(c.example);
  }
  return fmt::format("{} (e.g. {})", fmt::join(names, ","), fmt::join(example, ","));
}

std::string dotted_key(const RigField& f) {
  return f.section.empty() ? std::string(f.key) : fmt::format("{}.{}", f.section, f.key);
}

}  // namespace chutelab::validation
