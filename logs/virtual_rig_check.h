#pragma once
// The log import against the virtual rig's known truth, seed after seed: how often the stated
// ±2 u covers the true mean, and how often a log is flagged for drift or creep. The bench
// (bench/LOGS.md) runs it on 100 seeds, the suite on fewer.
#include <cstdint>
#include <filesystem>
#include <map>
#include <string>

#include "core/quantity.h"
#include "logs/sensor_model.h"
#include "logs/virtual_rig.h"

namespace chutelab::logs {

struct TrialCounts {
  int logs = 0;
  int flagged = 0, drift_flagged = 0, creep_flagged = 0;
  int warned_short = 0;
  std::map<Quantity, int> covered, read;   // ±2 u holds the truth / a value was read
  std::map<Quantity, double> sum_z2;       // sum of ((value - truth) / u)^2
  std::map<Quantity, double> sum_rel_u;    // sum of u / |truth|
  int speed_off = 0;                       // the tachometer disagreed with the record
};

// Logs of `truth` through `model` for seeds first..first+count-1, the sampling rate cycling through
// `rates_hz` (one per seed), each written into `scratch` (a folder) and read back by the import.
TrialCounts run_trials(const TrueCondition& truth, SensorModel model, std::uint64_t first, int count,
                       const std::vector<double>& rates_hz, const std::filesystem::path& scratch,
                       const Fluctuation* fluctuation = nullptr);

}  // namespace chutelab::logs
