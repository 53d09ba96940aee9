#pragma once
// Reads a whole string as a number: the one rule for CSV cells, command-line lists and study files,
// so "5.6mm" or "1,2" is never half-read. Infinity and NaN are numbers here; callers that need a
// finite value say so in their own message. And writes one for a message a person reads.
#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <fmt/format.h>
#include <optional>
#include <string>
#include <string_view>

namespace chutelab {

inline std::optional<double> parse_number(std::string_view s) {
  if (!s.empty() && s.front() == '+') s.remove_prefix(1);  // from_chars takes no leading '+'
  if (s.empty()) return std::nullopt;
  double v = 0.0;
#if defined(__EMSCRIPTEN__)
  // The libc++ of Debian's emscripten (3.1.6) has no floating-point from_chars. strtod in the C
  // locale (the page never sets another) reads the same numbers once what from_chars refuses
  // (leading space, hexadecimal) is refused here first.
  if (std::isspace(static_cast<unsigned char>(s.front())) || s.find_first_of("xX") != std::string_view::npos)
    return std::nullopt;
  const std::string copy(s);
  char* end = nullptr;
  v = std::strtod(copy.c_str(), &end);
  if (end != copy.c_str() + copy.size()) return std::nullopt;
#else
  const auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc() || ptr != s.data() + s.size()) return std::nullopt;
#endif
  return v;
}

// A number in a message (a tolerance's verdict, the JUnit file): four significant digits, fixed
// notation from 1e-4 to 1e6 (an exponent past them), no trailing zeros: "22.78", "0.08", "7", never
// the "7.000000000000001" of 100 * 0.07. The CSVs carry every digit.
inline std::string message_number(double v) {
  if (!std::isfinite(v)) return fmt::format("{}", v);
  if (v == 0.0) return "0";
  const int mag = static_cast<int>(std::floor(std::log10(std::abs(v))));
  if (mag < -4 || mag > 6) return fmt::format("{:.3e}", v);
  std::string s = fmt::format("{:.{}f}", v, std::clamp(3 - mag, 0, 7));
  if (s.find('.') != std::string::npos) {
    s.erase(s.find_last_not_of('0') + 1);
    if (s.back() == '.') s.pop_back();
  }
  return s == "-0" ? "0" : s;
}

}  // namespace chutelab
