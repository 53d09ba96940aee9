// The import-digitised mapping (TOML), applied to the example's curves on the bundled LIGGGHTS rig,
// as `chutelab import-digitised --mapping FILE` does before it writes anything.
#include "fuzz_common.h"
#include "validation/dataset.h"
#include "validation/digitised.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace chutelab;
  static const std::filesystem::path src = CHUTELAB_SOURCE_DIR;
  static const validation::Dataset rig =
      validation::read_dataset(src / "datasets" / "liggghts-rig", validation::MeasurementsRequired::no);
  static const std::vector<validation::DigitisedCurve> curves = [] {
    auto a = validation::read_digitised(src / "datasets" / "digitised-example" / "fig-a-stream-limits.csv");
    auto b = validation::read_digitised(src / "datasets" / "digitised-example" / "fig-b-forces.json");
    a.insert(a.end(), b.begin(), b.end());
    return a;
  }();
  const auto f = fuzz::scratch() / "mapping.toml";
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  fuzz::check_toml_scanner(text);
  fuzz::write_file(f, text);
  return fuzz::guarded([&] { (void)validation::import_digitised(rig, f, curves); });
}
