#pragma once
// Names are data: a condition, a model or a curve may be called "../../ds", "/etc", "." or
// "a/b". Whenever such a name becomes part of a path (the DEM's per-condition folders under
// OUT/dem/), it goes through file_name_for(), which maps every string to one plain path component:
// letters, digits, '-', '_' and '.' stay; every other byte is %XX (so the map is one-to-one and no
// two names share a file); a leading '.' is %2E (no hidden entries, never "." or ".."); a name too
// long for a file system is cut and given a hash of the whole. The result never holds a separator.
#include <cstdint>
#include <string>
#include <string_view>

#include <fmt/format.h>

namespace chutelab {

inline std::string file_name_for(std::string_view name) {
  constexpr std::size_t kMax = 120;  // file systems allow 255 bytes; room for suffixes
  std::string out;
  for (std::size_t i = 0; i < name.size(); ++i) {
    const auto c = static_cast<unsigned char>(name[i]);
    const bool plain = (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '-' ||
                       c == '_' || (c == '.' && i > 0);
    if (plain) out += static_cast<char>(c);
    else out += fmt::format("%{:02X}", c);
  }
  if (out.empty()) return "%";  // the empty name ('%' alone is no escape, so nothing else maps here)
  if (out.size() > kMax) {
    std::uint64_t h = 1469598103934665603ull;  // FNV-1a of the whole name
    for (unsigned char c : name) h = (h ^ c) * 1099511628211ull;
    std::size_t cut = kMax - 17;
    while (cut > 0 && out[cut - 1] == '%') --cut;  // never split an escape
    if (cut > 1 && out[cut - 2] == '%') cut -= 2;
    out = fmt::format("{}~{:016x}", out.substr(0, cut), h);
  }
  return out;
}

}  // namespace chutelab
