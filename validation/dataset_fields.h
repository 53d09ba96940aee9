#pragma once
// Every column of a dataset's CSV files, in the readers' own tables: validation/dataset.cpp reads by
// them (required columns, optional columns, the layout a missing column's message shows), and the
// dataset reference and `chutelab init`'s skeleton are written from them
// (validation/dataset_reference.h), so none can drift from the others.
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "core/rig.h"
#include "validation/dataset.h"

namespace chutelab::validation {

struct ColumnSpec {
  std::string_view name;
  bool required;
  std::string_view unit;     // "" for a name or a dimensionless number
  std::string_view meaning;
  std::string_view example;  // a cell of the example row
};

// conditions.csv's own columns (the operating point of each test); a row's other columns are the
// input uncertainties (operating_uncertainty_columns) and the setup's overrides (core/rig.h).
std::span<const ColumnSpec> condition_columns();
// The operating inputs' uncertainty columns of conditions.csv, one standard deviation each, and the
// top-level [uncertainty] key of setup.toml that sets their default.
struct UncertaintyColumn {
  std::string_view column, setup_key, unit;
  double to_si;
  std::optional<double> InputUncertainties::*member;
  double span;  // the widest uncertainty that still leaves a rig (check_operating_input's range), in `unit`
};
std::span<const UncertaintyColumn> operating_uncertainty_columns();
std::span<const ColumnSpec> measurement_columns();
std::span<const ColumnSpec> trajectory_columns();
std::span<const ColumnSpec> plate_map_columns();
// The names of the required columns of a table, in its order.
std::vector<std::string_view> required_columns(std::span<const ColumnSpec> columns);
// "condition,quantity,value,uncertainty (e.g. V2-26,normal_force_N,14.91,0.30)": the layout a file's
// missing column is explained with.
std::string layout_of(std::span<const ColumnSpec> columns);

// setup.toml's texts outside the tables.
std::span<const ColumnSpec> setup_texts();
// "material.friction_plate", or "gravity_mps2" for a top-level key.
std::string dotted_key(const RigField& f);

}  // namespace chutelab::validation
