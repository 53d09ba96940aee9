#pragma once
// Reads a whole string as a number: the one rule for CSV cells, command-line lists and study files,
// so "5.6mm" or "1,2" is never half-read. Infinity and NaN are numbers here; callers that need a
// finite value say so in their own message.
#include <charconv>
#include <optional>
#include <string_view>

namespace chutelab {

inline std::optional<double> parse_number(std::string_view s) {
  if (!s.empty() && s.front() == '+') s.remove_prefix(1);  // from_chars takes no leading '+'
  if (s.empty()) return std::nullopt;
  double v = 0.0;
  const auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc() || ptr != s.data() + s.size()) return std::nullopt;
  return v;
}

}  // namespace chutelab
