#pragma once
// import-digitised: curves digitised from published figures (WebPlotDigitizer's CSV export or
// project JSON) become trajectory.csv / measurements.csv rows of a new dataset folder, the source
// dataset plus the imported rows, read back by the strict reader before it is placed.
#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

namespace chutelab::api {

// Errors name the keys "out", the mapping's keys and the digitised points (file and line).
struct ImportDigitisedOptions {
  std::filesystem::path dataset;               // whose setup.toml and conditions.csv the curves belong to
  std::filesystem::path mapping;               // TOML: which curve is which condition and boundary or quantity
  std::vector<std::filesystem::path> inputs;   // WebPlotDigitizer CSV exports or project .json files
  std::filesystem::path out;                   // the new dataset folder: absent or empty
};

struct ImportDigitisedResult {
  std::vector<std::string> summary;   // one line per curve: what it became
  std::vector<std::string> unmapped;  // curves in the inputs that the mapping does not use
  std::size_t measurements = 0, trajectory_points = 0;
};

// Writes the folder o.out all or nothing (core/output_folder.h). A row that would not read back is
// said against its digitised point, any other problem against the source file it came from.
ImportDigitisedResult import_digitised(const ImportDigitisedOptions& o);

}  // namespace chutelab::api
