#include "api/setup.h"

#include "validation/dataset.h"

namespace chutelab::api {

Setup read_setup(const std::filesystem::path& file) { return validation::read_setup(file); }

Station read_condition(const std::filesystem::path& dir, const Setup& setup, std::string_view condition,
                       std::string_view field) {
  const std::filesystem::path file = dir / "conditions.csv";
  const auto rows = validation::read_conditions(file, setup);
  return validation::condition_row(rows, condition, file, field);
}

std::vector<OperatingLimit> operating_limits() {
  std::vector<OperatingLimit> out;
  for (const auto& l : validation::operating_limits()) out.push_back({std::string(l.column), l.min, l.min_open, l.max});
  return out;
}

}  // namespace chutelab::api
