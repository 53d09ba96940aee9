#include "validation/dataset_output.h"

#include "core/output_folder.h"

namespace chutelab::validation {

std::vector<std::filesystem::path> dataset_files(const std::filesystem::path& dir) {
  if (dir.empty()) return {};  // a dataset in memory (Python's, synthesized without a folder)
  return {dir, dir / "setup.toml", dir / "conditions.csv", dir / "measurements.csv", dir / "trajectory.csv",
          dir / "plate_map.csv", dir / "tolerances.toml", dir / "README.md", dir / "logs"};
}

void write_dataset(const std::filesystem::path& out, const std::vector<OutputFile>& files,
                   const std::filesystem::path& source_dir, std::string_view command) {
  OutputFolder folder(out, dataset_files(source_dir), command);
  // The folder is one dataset, whichever of these made it before.
  folder.takes_over({"synthesize", "synthesize-logs", "import-logs"});
  folder.read_together({"setup.toml", "conditions.csv", "measurements.csv", "trajectory.csv", "plate_map.csv",
                        "tolerances.toml", "README.md", "log_provenance.csv", "log_checks.csv", "logs"});
  for (const auto& [name, content] : files) folder.write(name, content);
  folder.commit();
}

}  // namespace chutelab::validation
