#pragma once
// estimate: the analytical answer (Booth/CEMA + Korzen) for one condition, in milliseconds. What
// the command line's `estimate`, the designer's page and the Python package all call.
//
//   api::EstimateOptions o;
//   o.dataset = "datasets/grima2010";
//   o.condition = "V5-44";
//   o.effects = {"air_drag=0.5"};
//   const api::EstimateResult r = api::estimate(o);   // throws InputError, key "belt_speed", ...
//   r.json();
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "analytical/transfer_station.h"
#include "api/estimate_output.h"
#include "effects/registry.h"

namespace chutelab::validation {
struct Dataset;
}

namespace chutelab::api {

// The stream's lines under the library's names (each said by name(), found beside its type).
using Streamline = analytical::Streamline;
using analytical::kAllStreamlines;

// What to estimate. Boundary units (m/s, t/h, mm), as a conditions.csv row. Errors name the keys
// "dataset", "setup", "condition", "belt_speed", "mass_flow", "plate_distance", "plate_top",
// "stream_thickness", "pulley_diameter", "belt_width", "bulk_density", "effect".
struct EstimateOptions {
  std::filesystem::path dataset, setup;   // a dataset folder, or a setup.toml alone (not both)
  const validation::Dataset* dataset_read = nullptr;  // a dataset already read, in place of `dataset`
  std::string condition;                  // start from this row of the dataset's conditions.csv
  std::filesystem::path default_dataset;  // used when neither dataset nor setup is given
  std::optional<double> belt_speed, mass_flow, plate_distance, plate_top, stream_thickness;
  // The rig's common geometry and material on top of the setup (or the row): mm, mm, kg/m^3.
  std::optional<double> pulley_diameter, belt_width, bulk_density;
  std::vector<std::string> effects;       // "NAME=VALUE"
};

// The options alone, before any file is read: contradictions, values out of bounds, effects that
// do not parse. Throws InputError naming the key.
void check(const EstimateOptions& o);

// What one point of an estimate gives: the analysis and each analytical model's reading.
struct EstimatePoint {
  analytical::TransferAnalysis analysis;
  ModelValues models;
};

// The station the options describe: a dataset row (condition) with the given values on top, or the
// values on a setup. Throws InputError naming the key.
Station resolve_station(const EstimateOptions& o);

// The analytical chain and every analytical model at one station, measurement effects applied.
EstimatePoint estimate_point(const Station& station, const analytical::EffectList& effects);

struct EstimateResult {
  analytical::TransferAnalysis analysis;
  ModelValues models;                      // the analytical models' values, effects applied
  std::vector<effects::EffectSetting> settings;
  std::string table() const { return estimate_table(analysis, models, settings); }
  std::string csv() const { return estimate_csv(analysis, models); }
  std::string json() const { return estimate_json(analysis, models, settings); }
  // The design drawn (pulley, streamlines, plate, impact point, Korzen readout) as a standalone SVG
  // file; as ASCII DXF R12 for CAD (mm, origin at the pulley centre); the streamlines' points as CSV.
  std::string svg() const;
  std::string dxf() const;
  std::string points_csv() const { return streamline_points_csv(analysis); }
  // One streamline as drawn (the points of points_csv(), the DXF and the JSON), m.
  std::vector<Eigen::Vector2d> path(analytical::Streamline which) const;
};

// check(o), then the estimate. Throws InputError for a missing or impossible input.
EstimateResult estimate(const EstimateOptions& o);

}  // namespace chutelab::api
