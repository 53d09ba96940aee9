// The dataset reader over all its files: setup.toml, conditions.csv, measurements.csv,
// trajectory.csv and plate_map.csv, given in one input separated by "%%" lines (a missing part = an
// absent file).
#include "fuzz_common.h"
#include "validation/dataset.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace chutelab;
  const auto parts = fuzz::split_parts({reinterpret_cast<const char*>(data), size}, 5);
  const auto dir = fuzz::scratch() / "dataset";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const char* names[] = {"setup.toml", "conditions.csv", "measurements.csv", "trajectory.csv", "plate_map.csv"};
  for (std::size_t i = 0; i < parts.size(); ++i) fuzz::write_file(dir / names[i], parts[i]);
  return fuzz::guarded([&] { (void)validation::read_dataset(dir, validation::MeasurementsRequired::no); });
}
