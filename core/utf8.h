#pragma once
// Text from users' files goes into UTF-8 reports and CSVs. A byte sequence that is not UTF-8 is,
// in spreadsheet exports, almost always Latin-1 / Windows-1252 ("Düsseldorf" saved by an old
// Excel): such bytes are read as Latin-1 code points, so the name survives, and the output stays
// valid UTF-8 whatever came in. C0 controls other than tab become U+FFFD (they have no place in a name).
#include <string>
#include <string_view>

namespace chutelab {

// Length of the well-formed UTF-8 sequence at s[i] (1-4), or 0 when it is not one (overlongs,
// surrogates and code points above U+10FFFF included).
inline std::size_t utf8_sequence(std::string_view s, std::size_t i) {
  const auto b = [&](std::size_t k) { return static_cast<unsigned char>(s[k]); };
  const unsigned char c = b(i);
  if (c < 0x80) return 1;
  std::size_t n = c >= 0xF0 ? 4 : c >= 0xE0 ? 3 : c >= 0xC2 ? 2 : 0;
  if (n == 0 || c > 0xF4 || i + n > s.size()) return 0;
  for (std::size_t k = 1; k < n; ++k)
    if ((b(i + k) & 0xC0) != 0x80) return 0;
  if (c == 0xE0 && b(i + 1) < 0xA0) return 0;   // overlong
  if (c == 0xED && b(i + 1) >= 0xA0) return 0;  // surrogate
  if (c == 0xF0 && b(i + 1) < 0x90) return 0;   // overlong
  if (c == 0xF4 && b(i + 1) >= 0x90) return 0;  // above U+10FFFF
  return n;
}

inline bool valid_utf8(std::string_view s) {
  for (std::size_t i = 0; i < s.size();) {
    const std::size_t n = utf8_sequence(s, i);
    if (n == 0) return false;
    i += n;
  }
  return true;
}

inline std::string to_utf8(std::string_view s) {
  std::string out;
  out.reserve(s.size());
  for (std::size_t i = 0; i < s.size();) {
    const auto c = static_cast<unsigned char>(s[i]);
    if (c < 0x20 && c != '\t' && c != '\n' && c != '\r') {
      out += "\xEF\xBF\xBD";
      ++i;
      continue;
    }
    if (const std::size_t n = utf8_sequence(s, i)) {
      out.append(s.substr(i, n));
      i += n;
      continue;
    }
    out += static_cast<char>(0xC0 | (c >> 6));  // Latin-1 byte as its code point
    out += static_cast<char>(0x80 | (c & 0x3F));
    ++i;
  }
  return out;
}

}  // namespace chutelab
