#pragma once
// The models' misfit in the words of the quantity: per measured quantity, how far off the model
// that judges it is on average and where it is off the most, in per cent of the measured value
// (forces, speeds, flows) or in the quantity's unit (heights and positions, whose zero is arbitrary).
// Each value is judged by the first model in registry order that predicts it, as in the combined
// RMS E/u_val (ValidationResult::combined_rms_normalised), so one line per quantity tells what the
// models together get wrong. A bulk-handling engineer acts on "6 % high at 5 m/s", not on chi^2.
#include <optional>
#include <string>
#include <vector>

#include "validation/harness.h"

namespace chutelab::validation {

struct QuantityMisfit {
  std::string quantity;            // boundary name, e.g. "normal_force_N", "trajectory_upper_y_mm"
  std::string symbol;              // "R_n", "y_upper"
  std::string label;               // "plate normal force", "upper stream boundary"
  std::string unit;                // boundary unit
  std::string model;               // the model that judges it
  int n = 0;                       // compared values with a normalised error
  bool in_percent = false;         // errors relative to the measured value
  double mean_error = 0.0;         // fraction (in_percent) or boundary unit; E = predicted - measured
  double rms_normalised = 0.0;     // RMS of E/u_val
  double mean_normalised = 0.0;
  std::string worst_condition;     // the value of largest |error| (in per cent or the unit)
  double worst_error = 0.0;        // as mean_error
  double worst_normalised = 0.0;   // its E/u_val
  // More than the stated uncertainties explain: sum of (E/u_val)^2 beyond chi^2's 99th percentile
  // for n values, or the worst value beyond 4 u_val.
  bool beyond_noise = false;
};

// One entry per compared quantity, in the vocabulary's order (trajectory boundaries last).
std::vector<QuantityMisfit> quantity_misfits(const ValidationResult& r);

// The same quantity in another result (e.g. after adding effects), judged by the same model.
std::optional<QuantityMisfit> find_misfit(const std::vector<QuantityMisfit>& all, const std::string& quantity);

// "+6.1 %", "-3.2 mm": an error in the entry's own terms.
std::string signed_amount(const QuantityMisfit& m, double value);
// "6.1 % high", "3.2 mm low", "within 0.1 %" (below the display precision).
std::string amount_words(const QuantityMisfit& m, double value);

}  // namespace chutelab::validation
