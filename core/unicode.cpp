#include "core/unicode.h"

#include <algorithm>
#include <cstdint>
#include <iterator>
#include <vector>

#include "core/utf8.h"

namespace chutelab {
namespace {

#include "core/unicode_tables.inc"

// Format characters that draw nothing (Unicode's Default_Ignorable_Code_Point, the ones a name
// could carry by a paste or an attack).
bool invisible(std::uint32_t c) {
  return c == 0x00AD || c == 0x034F || c == 0x061C || c == 0x115F || c == 0x1160 || c == 0x17B4 || c == 0x17B5 ||
         (c >= 0x180B && c <= 0x180F) || (c >= 0x200B && c <= 0x200F) || (c >= 0x202A && c <= 0x202E) ||
         (c >= 0x2060 && c <= 0x206F) || c == 0x3164 || (c >= 0xFE00 && c <= 0xFE0F) || c == 0xFEFF ||
         c == 0xFFA0 || (c >= 0x1BCA0 && c <= 0x1BCA3) || (c >= 0x1D173 && c <= 0x1D17A) ||
         (c >= 0xE0000 && c <= 0xE0FFF);
}

// Unicode's White_Space.
bool space(std::uint32_t c) {
  return (c >= 0x09 && c <= 0x0D) || c == 0x20 || c == 0x85 || c == 0xA0 || c == 0x1680 ||
         (c >= 0x2000 && c <= 0x200A) || c == 0x2028 || c == 0x2029 || c == 0x202F || c == 0x205F || c == 0x3000;
}

int combining_class(std::uint32_t c) {
  const auto* end = std::end(kCombiningClass);
  const auto* it = std::upper_bound(std::begin(kCombiningClass), end, c,
                                    [](std::uint32_t v, const std::uint32_t(&r)[3]) { return v < r[0]; });
  if (it == std::begin(kCombiningClass)) return 0;
  --it;
  return c <= (*it)[1] ? static_cast<int>((*it)[2]) : 0;
}

void decompose(std::uint32_t c, std::vector<std::uint32_t>& out) {
  // Hangul syllables decompose by arithmetic (The Unicode Standard, 3.12).
  constexpr std::uint32_t kS = 0xAC00, kL = 0x1100, kV = 0x1161, kT = 0x11A7, kVCount = 21, kTCount = 28;
  if (c >= kS && c < kS + 11172) {
    const std::uint32_t s = c - kS;
    out.push_back(kL + s / (kVCount * kTCount));
    out.push_back(kV + (s % (kVCount * kTCount)) / kTCount);
    if (s % kTCount) out.push_back(kT + s % kTCount);
    return;
  }
  const auto* end = std::end(kCanonicalDecomposition);
  const auto* it = std::lower_bound(std::begin(kCanonicalDecomposition), end, c,
                                    [](const std::uint32_t(&r)[3], std::uint32_t v) { return r[0] < v; });
  if (it == end || (*it)[0] != c) {
    out.push_back(c);
    return;
  }
  decompose((*it)[1], out);
  if ((*it)[2]) decompose((*it)[2], out);
}

void append_utf8(std::uint32_t c, std::string& o) {
  if (c < 0x80) {
    o += static_cast<char>(c);
  } else if (c < 0x800) {
    o += static_cast<char>(0xC0 | (c >> 6));
    o += static_cast<char>(0x80 | (c & 0x3F));
  } else if (c < 0x10000) {
    o += static_cast<char>(0xE0 | (c >> 12));
    o += static_cast<char>(0x80 | ((c >> 6) & 0x3F));
    o += static_cast<char>(0x80 | (c & 0x3F));
  } else {
    o += static_cast<char>(0xF0 | (c >> 18));
    o += static_cast<char>(0x80 | ((c >> 12) & 0x3F));
    o += static_cast<char>(0x80 | ((c >> 6) & 0x3F));
    o += static_cast<char>(0x80 | (c & 0x3F));
  }
}

}  // namespace

std::string printed_form(std::string_view text) {
  const std::string s = to_utf8(text);
  std::vector<std::uint32_t> cps;
  for (std::size_t i = 0; i < s.size();) {
    const std::size_t n = utf8_sequence(s, i);  // to_utf8 left only well-formed sequences
    const auto b = [&](std::size_t k) { return static_cast<std::uint32_t>(static_cast<unsigned char>(s[i + k])); };
    std::uint32_t c = n == 1 ? b(0)
                      : n == 2 ? ((b(0) & 0x1F) << 6) | (b(1) & 0x3F)
                      : n == 3 ? ((b(0) & 0x0F) << 12) | ((b(1) & 0x3F) << 6) | (b(2) & 0x3F)
                               : ((b(0) & 0x07) << 18) | ((b(1) & 0x3F) << 12) | ((b(2) & 0x3F) << 6) | (b(3) & 0x3F);
    i += n == 0 ? 1 : n;
    if (invisible(c)) continue;
    if (space(c)) c = ' ';
    decompose(c, cps);
  }
  // Canonical order: each run of combining marks sorted by class (stable, as the standard asks).
  for (std::size_t i = 0; i < cps.size();) {
    if (combining_class(cps[i]) == 0) {
      ++i;
      continue;
    }
    std::size_t j = i;
    while (j < cps.size() && combining_class(cps[j]) != 0) ++j;
    std::stable_sort(cps.begin() + static_cast<std::ptrdiff_t>(i), cps.begin() + static_cast<std::ptrdiff_t>(j),
                     [](std::uint32_t a, std::uint32_t b) { return combining_class(a) < combining_class(b); });
    i = j;
  }
  std::size_t first = 0, last = cps.size();
  while (first < last && cps[first] == ' ') ++first;
  while (last > first && cps[last - 1] == ' ') --last;
  std::string o;
  for (std::size_t k = first; k < last; ++k) append_utf8(cps[k], o);
  return o;
}

}  // namespace chutelab
