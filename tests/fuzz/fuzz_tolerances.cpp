// tolerances.toml.
#include "fuzz_common.h"
#include "validation/tolerances.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace chutelab;
  const auto f = fuzz::scratch() / "tolerances.toml";
  fuzz::write_file(f, {reinterpret_cast<const char*>(data), size});
  return fuzz::guarded([&] { (void)validation::Tolerances::read(f); });
}
