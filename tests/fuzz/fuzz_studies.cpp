// The study CSVs read by `validate --studies`: calibration.csv and sensitivity.csv. The first byte
// picks which file the rest becomes (even: calibration, odd: sensitivity).
#include "fuzz_common.h"
#include "reports/studies.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace chutelab;
  if (size == 0) return 0;
  const auto dir = fuzz::scratch() / "study";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const char* name = (data[0] & 1) ? "sensitivity.csv" : "calibration.csv";
  fuzz::write_file(dir / name, {reinterpret_cast<const char*>(data + 1), size - 1});
  return fuzz::guarded([&] { (void)reports::read_studies({dir}, "grima2010"); });
}
