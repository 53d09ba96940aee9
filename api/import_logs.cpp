#include "api/import_logs.h"

#include <fmt/format.h>
#include <fstream>
#include <sstream>

#include "core/input_error.h"
#include "core/utf8.h"
#include "logs/provenance_csv.h"
#include "validation/dataset_output.h"

namespace chutelab::api {
namespace {

std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return to_utf8(ss.str());
}

}  // namespace

void check(const ImportLogsOptions& o) {
  if (o.dataset.empty()) throw InputError("", 0, "dataset", "give the dataset folder that holds logs/");
}

ImportLogsResult import_logs(const ImportLogsOptions& o) {
  check(o);
  ImportLogsResult r;
  if (!logs::has_logs(o.dataset)) {
    // Read the folder first so that a missing or broken dataset is said as such.
    validation::read_dataset(o.dataset, validation::MeasurementsRequired::no);
    throw InputError((o.dataset / "logs" / "layout.toml").string(), 0, "dataset",
                     "file not found: a dataset of logs has logs/layout.toml and one logs/<condition>.csv a condition");
  }
  std::optional<logs::LogImport> li;
  r.dataset = logs::read_dataset(o.dataset, validation::MeasurementsRequired::no, &li);
  r.logs = std::move(*li);
  if (o.prepare_output) {
    OutputPlan plan;
    plan.inputs = validation::dataset_files(o.dataset);
    plan.files = {"setup.toml", "conditions.csv", "measurements.csv", "log_provenance.csv", "log_checks.csv", "README.md"};
    o.prepare_output(plan);
  }
  return r;
}

std::vector<validation::OutputFile> ImportLogsResult::files() const {
  namespace fs = std::filesystem;
  const fs::path& dir = dataset.dir;
  std::vector<validation::OutputFile> out = {{"setup.toml", slurp(dir / "setup.toml")},
                                             {"conditions.csv", slurp(dir / "conditions.csv")},
                                             {"measurements.csv", logs::measurements_csv(dataset, logs)},
                                             {"log_provenance.csv", logs::log_provenance_csv(logs)},
                                             {"log_checks.csv", logs::log_checks_csv(logs)}};
  for (const char* f : {"trajectory.csv", "plate_map.csv", "tolerances.toml"}) {
    std::error_code ec;
    if (fs::exists(fs::symlink_status(dir / f, ec))) out.emplace_back(f, slurp(dir / f));
  }
  std::string readme;
  {
    std::error_code ec;
    if (fs::exists(fs::symlink_status(dir / "README.md", ec))) readme = slurp(dir / "README.md") + "\n";
  }
  readme += fmt::format(
      "## Means from the logs\n\n"
      "The plate's quantities in measurements.csv were read from the rig's logs (`chutelab import-logs`): "
      "each row names its log, its steady window and its method; log_provenance.csv holds every number behind "
      "each mean (the zeros and their drift, the creep, the autocorrelation time, the parts of the uncertainty) "
      "and log_checks.csv the belt's own channels against the recorded operating point.\n");
  const auto warnings = logs.warnings();
  if (!warnings.empty()) {
    readme += "\nWhat the logs said about themselves:\n\n";
    for (const auto& w : warnings) readme += "- " + w + "\n";
  }
  out.emplace_back("README.md", readme);
  return out;
}

}  // namespace chutelab::api
