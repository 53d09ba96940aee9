// A DEM cache entry (dem/station/cache.h) as a file in the cache folder, looked up under the key it
// states (or another when it states none), and its text read as a result body. An entry is whole
// or refused; the only acceptable outcomes are a result or a refusal, never an exception. What is
// accepted must be what the writer writes: its text read back gives the same text.
#include <cstdlib>

#include "dem/station/cache.h"
#include "fuzz_common.h"

namespace {

// The key an entry states on its second line ("key <bytes>") and after it, when it states one.
std::string stated_key(std::string_view s) {
  const std::size_t nl1 = s.find('\n');
  if (nl1 == std::string_view::npos || s.substr(nl1 + 1, 4) != "key ") return "fuzz key\n";
  const std::size_t nl2 = s.find('\n', nl1 + 1);
  if (nl2 == std::string_view::npos) return "fuzz key\n";
  std::size_t bytes = 0;
  for (char c : s.substr(nl1 + 5, nl2 - nl1 - 5)) {
    if (c < '0' || c > '9' || bytes > s.size()) return "fuzz key\n";
    bytes = bytes * 10 + static_cast<std::size_t>(c - '0');
  }
  return std::string(s.substr(nl2 + 1, bytes));
}

void round_trip(const chutelab::dem::station::StationResult& r) {
  using namespace chutelab::dem::station;
  const std::string text = to_text(r);
  chutelab::dem::station::TextProblem why;
  const auto back = from_text(text, &why);
  if (!back || to_text(*back) != text) {
    std::fprintf(stderr, "fuzz: an accepted result does not read back as written (line %ld, %s: %s)\n", why.line,
                 why.field.c_str(), why.problem.c_str());
    std::abort();
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace chutelab;
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  const dem::station::ResultCache cache(fuzz::scratch().string());
  const std::string key = stated_key(text);
  const std::string file = cache.path_for(key);
  fuzz::write_file(file, text);
  fuzz::guarded([&] {
    const dem::station::CacheEntry e = cache.lookup(key);
    if (e.result && e.refused) std::abort();
    if (e.result) round_trip(*e.result);
    if (auto body = dem::station::from_text(std::string(text))) round_trip(*body);
  });
  std::filesystem::remove(file);  // one file a key: the folder would fill up
  return 0;
}
