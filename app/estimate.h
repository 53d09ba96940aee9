#pragma once
// The analytical answer for one condition, shared by `chutelab estimate` and the Python package so
// that both resolve their inputs and compute the same way.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "analytical/transfer_station.h"
#include "app/output.h"
#include "effects/registry.h"

namespace chutelab::app {

// Boundary units, as the command-line flags (m/s, t/h, mm). Errors name the flag (--belt-speed, ...).
struct EstimateInput {
  std::string dataset, setup_file, condition;
  std::filesystem::path default_dataset;  // used when neither dataset nor setup_file is given
  std::optional<double> belt_speed, mass_flow, plate_distance, plate_top, stream_thickness;
  std::vector<std::string> effects;       // "NAME=VALUE"
};

// What one point of an estimate gives: the analysis and each analytical model's reading.
struct EstimatePoint {
  analytical::TransferAnalysis analysis;
  ModelValues models;
};

// The station the inputs describe: a dataset row (--condition) with the flags on top, or the flags
// on a setup. Throws InputError naming the flag.
Station resolve_station(const EstimateInput& input);

// The analytical chain and every analytical model at one station, measurement effects applied.
EstimatePoint estimate_point(const Station& station, const analytical::EffectList& effects);

struct Estimate {
  analytical::TransferAnalysis analysis;
  ModelValues models;                      // the analytical models' values, effects applied
  std::vector<effects::EffectSetting> settings;
};

// Throws InputError for a missing or impossible input.
Estimate estimate(const EstimateInput& input);

}  // namespace chutelab::app
