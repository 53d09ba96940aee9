#pragma once
// The numbers of a study's CSV (calibration.csv, sensitivity.csv), checked as a dataset's are: a
// count (particles, steps) is a whole number that fits its type, a physical value lies in its
// range. A file edited by hand or by a tool may hold 1e300 particles, which a cast would turn into
// -9223372036854775808 in the report.
#include <cmath>
#include <fmt/format.h>
#include <string>
#include <string_view>

#include "core/input_error.h"
#include "core/message.h"
#include "validation/csv_table.h"

namespace chutelab::studies {

// A whole number in [0, max].
inline long long csv_count(const validation::CsvTable& t, const validation::CsvRow& r, std::size_t col,
                           double max = 1e15) {
  const double v = t.number(r, col);
  if (!(v >= 0.0 && v <= max) || v != std::floor(v))
    throw InputError(t.file(), r.line, t.header().at(col),
                     fmt::format("must be a whole number from 0 to {:g}, got {}", max, shown(r.cells.at(col))));
  return static_cast<long long>(v);
}

// A number in [lo, hi] (NaN when the cell is empty and `optional`).
inline double csv_in_range(const validation::CsvTable& t, const validation::CsvRow& r, std::size_t col, double lo,
                           double hi, bool optional = false) {
  if (optional && r.cells.at(col).empty()) return std::nan("");
  const double v = t.number(r, col);
  if (!(v >= lo && v <= hi))
    throw InputError(t.file(), r.line, t.header().at(col),
                     fmt::format("must lie in [{:g}, {:g}], got {}", lo, hi, shown(r.cells.at(col))));
  return v;
}

// 0 or 1.
inline bool csv_flag(const validation::CsvTable& t, const validation::CsvRow& r, std::size_t col) {
  const double v = t.number(r, col);
  if (v != 0.0 && v != 1.0)
    throw InputError(t.file(), r.line, t.header().at(col), fmt::format("must be 0 or 1, got {}", shown(r.cells.at(col))));
  return v != 0.0;
}

}  // namespace chutelab::studies
