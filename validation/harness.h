#pragma once
// Run every condition of a dataset through every model and compare with the measurements.
// Errors follow ASME V&V 20-2009: comparison error E = S - D (prediction minus data) and the
// validation uncertainty u_val = sqrt(u_num_stat^2 + u_num_disc^2 + u_input^2 + u_D^2): u_num is
// what the model states about its own prediction, split into the statistical part (the DEM's
// standard error of the mean) and the discretisation part (one-factor ladders of the run's numerical
// choices: time step, and particle size when coarse-grained; validation/gci.h), both absent for analytical models; u_input is propagated from the dataset's
// stated input uncertainties (validation/input_uncertainty.h); u_D is the measurement's. A part
// that was not estimated is absent and counts as 0 in u_val (the report says which).
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "analytical/effect.h"
#include "validation/dataset.h"
#include "validation/model.h"
#include "validation/tolerances.h"

namespace chutelab::validation {

// A height (y_R, a stream boundary's y; by boundary name): its zero is the pulley's centre, so a per
// cent of it means nothing and its error is read in mm. Summaries and messages give it no relative
// error (errors.csv keeps E/|D| for every value, which a relative tolerance checks).
bool is_height(std::string_view quantity);

// One measured value against one model (quantities and trajectory points alike).
struct Comparison {
  std::string condition;
  std::string model;
  std::string quantity;          // boundary name, e.g. "normal_force_N" or "trajectory_upper_y_mm"
  std::optional<Quantity> q;     // set for the quantities of DESIGN.md §2
  std::optional<Boundary> boundary;  // set for trajectory points
  double x = 0.0;                // m, trajectory points only
  std::optional<double> plate_y, plate_z;  // m, plate-map points only
  double scale = 1.0;            // SI -> boundary unit
  double measured = 0.0;         // SI
  std::optional<double> uncertainty;       // u_D, SI
  std::optional<double> predicted;         // absent when the model does not predict it
  std::optional<double> prediction_uncertainty;  // u_num_stat (statistical part of u_num), SI
  std::optional<double> u_num_disc;              // discretisation part of u_num, SI
  std::optional<double> u_input;                 // SI
  const std::optional<double>& u_num_stat() const { return prediction_uncertainty; }
  double error() const { return *predicted - measured; }  // E = S - D
  std::optional<double> relative_error() const;
  // E / u_val: the one "normalised error" of chutelab (V&V 20). Absent without a prediction or
  // when u_val is unknown or zero. |E/u_val| > 2 is more than the stated uncertainties explain.
  std::optional<double> normalised_error() const;
  std::optional<double> validation_uncertainty() const;  // u_val; absent when no part is known
  std::optional<double> vv20_ratio() const;          // |E| / u_val, the same number unsigned
  std::string unit() const;      // boundary unit of the quantity ("N", "m/s", "mm", "Pa", ...)
  ToleranceVerdict verdict;      // filled when a tolerance applies
};

struct SummaryRow {
  std::string model, quantity;
  int n = 0;                     // compared values (with a prediction)
  double rms_error = 0.0;        // boundary unit
  std::optional<double> rms_normalised_error;
  std::optional<double> max_abs_relative_error;
  std::optional<bool> within_tolerance;  // absent when no tolerance was set
};

struct ConditionResult {
  std::string condition;
  std::string model;
  ModelPrediction prediction;    // effects (measurement ones too) applied
};

struct ValidationResult {
  std::string dataset_name;              // setup.toml `name` (the folder's name without one)
  std::string dataset_folder;            // the folder the user gave, by its last name: what titles say
  std::vector<std::string> models;
  std::vector<std::string> effects;      // "name=value" as applied
  std::vector<ConditionResult> predictions;
  std::vector<Comparison> comparisons;   // quantities first, then trajectory points
  std::vector<SummaryRow> summary;
  bool acceptance_checked = false;
  bool acceptance_failed = false;
  // Why acceptance failed without a value out of tolerance: a limit that checked no value (a model
  // that did not run, a quantity it does not predict or the dataset does not hold, no limit at all).
  // Acceptance that checked nothing is never a pass.
  std::vector<std::string> acceptance_problems;

  const ConditionResult* prediction(const std::string& condition, const std::string& model) const;
  // RMS of E/u_val over every comparison of a model that has an uncertainty.
  std::optional<double> overall_rms_normalised(const std::string& model) const;
  // The models used together as the reference study's hybrid: each measured value is judged by the first
  // model, in registry order (booth-cema, korzen, ...), that predicts it. This is the figure the
  // diagnosis works on.
  std::optional<double> combined_rms_normalised() const;
  // One line for a terminal: the folder, the counts and the RMS E/u_val per model and combined, and
  // the acceptance. `judged` false: this result is reported beside the acceptance, not judged by it
  // (the models with an effect fitted here, validate's contract): its count says so and never
  // "passed" or "FAILED".
  std::string brief(bool judged = true) const;
  // How many checked values are outside their tolerance.
  int failed_count() const;
  int checked_count() const;
};

struct ValidateOptions {
  analytical::EffectList effects;
  std::vector<std::string> effect_labels;
  const Tolerances* tolerances = nullptr;
  bool quiet = true;             // progress on stderr for slow models
  // Expensive runs side by side in this process (core/campaign.h); 0 or 1: in order. The
  // numbers do not depend on it.
  int jobs = 0;
};

// Throws InputError, located at the condition's line, when a model cannot handle a condition.
ValidationResult validate(const Dataset& d, const std::vector<ModelPtr>& models,
                          const ValidateOptions& options = {});

// Applies the measurement stage of the effects to the predictions of one condition (one entry per
// model), each model's values completed from the others first: the instrument is shared.
void apply_measurement_effects(const analytical::EffectList& effects,
                               std::span<ConditionResult> same_condition);

// The trajectory points a condition asks models for.
std::vector<TrajectoryQuery> trajectory_queries(const Dataset& d, const std::string& condition);
// The plate points (plate_map.csv) a condition asks models for, in dataset order.
std::vector<PlateQuery> plate_queries(const Dataset& d, const std::string& condition);

}  // namespace chutelab::validation
