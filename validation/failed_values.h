#pragma once
// The values outside their tolerance, as one table for a CI log (validate's console), report.md
// and report.html: condition, model, quantity, measured, predicted, the error in the quantity's
// unit and in per cent, and the limit that was broken, as an allowed error in the same unit (and
// in per cent of the measured value where that means something).
#include <string>
#include <vector>

#include "validation/harness.h"

namespace chutelab::validation {

struct FailedValue {
  std::string condition, model;
  std::string quantity;   // "R_s plate shear force", "y_upper upper stream boundary at x = 250 mm"
  std::string measured;   // "2.335 ± 0.047 N"
  std::string predicted;  // "3.900 N"
  std::string error;      // "+1.565 N (+67.0 %)"
  std::string limit;      // "±0.350 N (relative 15 %)"
};

// Every checked value outside its limits, in the order of the comparisons (quantities first).
std::vector<FailedValue> failed_values(const ValidationResult& r);

// An aligned plain-text table of at most max_rows rows (then one line saying how many more and
// where they are: `rest_in`), headed by one line with the counts. Empty when nothing failed.
std::string failure_table_text(const ValidationResult& r, std::size_t max_rows = 40,
                               const std::string& rest_in = "errors.csv, column tolerance, and in report.md");

}  // namespace chutelab::validation
