#pragma once
// synthesize_logs: the virtual rig (logs/virtual_rig.h). A dataset of logs written from a known
// truth, any model's prediction of each condition (a measurements-like CSV: condition, quantity,
// value, e.g. `synthesize --noise-scale 0`'s measurements.csv or another code's predictions.csv),
// through a sensor model (logs/sensor_model.h), optionally with the fluctuation of the DEM's own
// plate loads. The command line's `synthesize-logs` and the Python package's synthesize_logs() are
// this function.
#include <cstdint>
#include <filesystem>
#include <vector>

#include "api/output_plan.h"
#include "logs/sensor_model.h"
#include "logs/virtual_rig.h"
#include "validation/dataset.h"
#include "validation/output_files.h"

namespace chutelab::api {

// Errors name the keys "dataset", "truth", "sensor", "dem_series", "seed".
struct SynthesizeLogsOptions {
  std::filesystem::path dataset;     // the rig, its conditions (the record) and the measurements no log holds
  std::filesystem::path truth;       // condition,quantity,value: normal_force_N, shear_force_N, impact_point_y_mm
  std::filesystem::path sensor;      // the sensor model's TOML; "" = its defaults
  std::filesystem::path dem_series;  // "" or a folder of DEM runs: <condition>/timeseries.csv or <condition>.csv
  std::uint64_t seed = 1;
  PrepareOutput prepare_output;      // may be empty
};

void check(const SynthesizeLogsOptions& o);

struct SynthesizeLogsResult {
  validation::Dataset source;
  logs::SensorModel sensor;
  std::vector<logs::TrueCondition> truth;   // per condition, as written
  // setup.toml, conditions.csv, measurements.csv (the source's rows of quantities the logs do not
  // give), trajectory.csv and plate_map.csv as they were, the logs folder (layout.toml, <condition>.csv),
  // README.md. Write them with validation::write_dataset(out, files, source.dir, "synthesize-logs").
  std::vector<validation::OutputFile> files;
};

SynthesizeLogsResult synthesize_logs(const SynthesizeLogsOptions& o);

}  // namespace chutelab::api
