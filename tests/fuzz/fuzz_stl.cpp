// The STL reader (ASCII and binary), in mm as [dem.stl] meshes are read.
#include "dem/walls/stl.h"
#include "fuzz_common.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace chutelab;
  const auto f = fuzz::scratch() / "mesh.stl";
  fuzz::write_file(f, {reinterpret_cast<const char*>(data), size});
  return fuzz::guarded([&] { (void)dem::read_stl(f.string(), 1e-3); });
}
