#pragma once
// import_logs: a dataset whose plate measurements are a rig's raw logs (DATASET/logs/layout.toml and one
// logs/<condition>.csv a condition) turned into a dataset of means: measurements.csv with each
// row's provenance (file, window, method), log_provenance.csv with every number behind each mean
// and log_checks.csv with the belt's own channels against the record (logs/provenance_csv.h). The
// command line's `import-logs` and the Python package's import_logs() are this function.
#include <filesystem>
#include <vector>

#include "api/output_plan.h"
#include "logs/dataset_logs.h"
#include "validation/dataset.h"
#include "validation/output_files.h"

namespace chutelab::api {

// Errors name the key "dataset".
struct ImportLogsOptions {
  std::filesystem::path dataset;     // a dataset folder with logs/
  PrepareOutput prepare_output;      // may be empty
};

void check(const ImportLogsOptions& o);

struct ImportLogsResult {
  validation::Dataset dataset;       // as read, the logs' means among its measurements
  logs::LogImport logs;
  // The dataset of means: setup.toml, conditions.csv, measurements.csv, log_provenance.csv,
  // log_checks.csv, README.md, and trajectory.csv, plate_map.csv, tolerances.toml as they were.
  // Write them with validation::write_dataset(out, files, dataset.dir, "import-logs").
  std::vector<validation::OutputFile> files() const;
};

ImportLogsResult import_logs(const ImportLogsOptions& o);

}  // namespace chutelab::api
