#pragma once
// A dataset whose plate measurements come as logs: `DATASET/logs/layout.toml` and one `DATASET/logs/<condition>.csv`
// a condition of conditions.csv. Reading such a dataset reads the logs into means
// (log_reading.h) beside the rows of measurements.csv (the quantities no log holds: a camera's
// impact velocity, say), so that validate, diagnose and synthesize take it as any dataset.
// What the logs say about themselves (a drift, a creep, a belt speed off its record, a log too
// short) is printed as warnings when they are read: before any model runs.
#include <filesystem>
#include <optional>
#include <vector>

#include "logs/layout.h"
#include "logs/log_reading.h"
#include "validation/dataset.h"

namespace chutelab::logs {

struct LogImport {
  Layout layout;
  std::vector<ConditionReading> conditions;  // in conditions.csv order
  bool empty() const { return conditions.empty(); }
  std::vector<std::string> warnings() const;  // each prefixed with its log's file name
};

// Whether `dir` holds logs (dir/logs/layout.toml).
bool has_logs(const std::filesystem::path& dir);

// Reads every condition's log of the dataset `d` (its dir/logs). Each problem: one InputError.
LogImport import_logs(const validation::Dataset& d);

// The logs' means as measurements (one per condition and quantity), each named by its log file. A
// quantity that measurements.csv also gives for the condition is an InputError naming both.
void add_measurements(validation::Dataset& d, const LogImport& logs);

// validation::read_dataset, then the logs when the folder has them (printing their warnings);
// `need` counts the logs' measurements.
validation::Dataset read_dataset(const std::filesystem::path& dir, validation::MeasurementsRequired need,
                                 std::optional<LogImport>* logs = nullptr);

}  // namespace chutelab::logs
