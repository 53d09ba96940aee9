// tolerances.toml (validate --tolerances, Python validate(tolerances=...)).
#include "fuzz_common.h"
#include "validation/tolerances.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace chutelab;
  const auto f = fuzz::scratch() / "tolerances.toml";
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  fuzz::check_toml_scanner(text);
  fuzz::write_file(f, text);
  return fuzz::guarded([&] { (void)validation::Tolerances::read(f); });
}
