// The [dem] table of setup.toml, read and resolved against the presets as `simulate` does.
#include "dem/station/settings.h"
#include "fuzz_common.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace chutelab;
  const auto f = fuzz::scratch() / "setup.toml";
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  fuzz::check_toml_scanner(text);
  fuzz::write_file(f, text);
  return fuzz::guarded([&] {
    const auto t = dem::station::read_dem_table(f.string());
    (void)dem::station::resolve(t, {});
  });
}
