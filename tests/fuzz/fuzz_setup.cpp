// setup.toml alone, as every command and the Python package's read_dataset read it first (the rig
// fields, [uncertainty], the unknown-table checks); fuzz_dataset gives it with the CSV files.
#include "fuzz_common.h"
#include "validation/dataset.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace chutelab;
  const auto f = fuzz::scratch() / "setup.toml";
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  fuzz::check_toml_scanner(text);
  fuzz::write_file(f, text);
  return fuzz::guarded([&] {
    validation::InputUncertainties u;
    (void)validation::read_setup(f, &u);
  });
}
