#include "core/option_check.h"

#include <fmt/format.h>

#include <charconv>
#include <cmath>
#include <set>

#include "core/input_error.h"
#include "core/message.h"
#include "core/number.h"

namespace chutelab::options {
namespace {
constexpr double kNone = std::numeric_limits<double>::max();

std::string num(double v) { return fmt::format("{}", v); }
}  // namespace

std::string NumberRule::describe() const {
  const std::string what = whole ? "a whole number" : "a finite number";
  const bool has_lo = lo > -kNone, has_hi = hi < kNone;
  std::string range;
  const std::string hi_shown = hi_text.empty() ? num(hi) : std::string(hi_text);
  if (has_lo && has_hi)
    range = fmt::format(" in {}{}, {}{}", lo_open ? "(" : "[", num(lo), hi_shown, hi_open ? ")" : "]");
  else if (has_lo)
    range = fmt::format(" {} {}", lo_open ? ">" : ">=", num(lo));
  else if (has_hi)
    range = fmt::format(" {} {}", hi_open ? "<" : "<=", hi_shown);
  std::string out = what + range;
  if (!unit.empty()) out.append(" ").append(unit);
  return out;
}

double NumberRule::check(double v) const {
  const bool ok = std::isfinite(v) && (!whole || v == std::floor(v)) && (lo_open ? v > lo : v >= lo) &&
                  (hi_open ? v < hi : v <= hi);
  if (!ok) throw InputError("", 0, std::string(key), fmt::format("must be {}, got {}", describe(), num(v)));
  return v;
}

double NumberRule::check(std::string_view typed) const {
  // A whole number typed as digits is checked exactly (a 64-bit seed has more digits than a
  // double holds; 2^64 - 1 is a seed, 2^64 is not).
  const auto fail = [&] {
    return InputError("", 0, std::string(key), fmt::format("must be {}, got {}", describe(), shown(typed)));
  };
  std::string_view digits = typed;
  if (!digits.empty() && digits.front() == '+') digits.remove_prefix(1);
  const bool negative = !digits.empty() && digits.front() == '-';
  if (whole && !digits.empty() && digits.find_first_not_of("0123456789", negative ? 1 : 0) == std::string_view::npos &&
      digits.size() > (negative ? 1u : 0u)) {
    long double x = 0;
    if (negative) {
      long long n = 0;
      const auto [p, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), n);
      if (ec != std::errc() || p != digits.data() + digits.size()) throw fail();
      x = static_cast<long double>(n);
    } else {
      unsigned long long n = 0;
      const auto [p, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), n);
      if (ec != std::errc() || p != digits.data() + digits.size()) throw fail();
      x = static_cast<long double>(n);
    }
    const long double l = lo, h = hi;
    if (!(lo_open ? x > l : x >= l) || !(hi_open ? x < h : x <= h)) throw fail();
    return static_cast<double>(x);
  }
  const auto v = parse_number(typed);
  if (!v || !std::isfinite(*v))
    throw InputError("", 0, std::string(key), fmt::format("must be {}, got {}", describe(), shown(typed)));
  try {
    return check(*v);
  } catch (const InputError&) {
    throw InputError("", 0, std::string(key), fmt::format("must be {}, got {}", describe(), shown(typed)));
  }
}

void non_empty(std::string_view key, std::string_view value) {
  if (value.empty())
    throw InputError("", 0, std::string(key), "is empty; give a value or leave the option out");
}

std::vector<std::string> list(std::string_view key, std::string_view text) {
  std::vector<std::string> out;
  std::set<std::string> seen;
  if (text.empty()) throw InputError("", 0, std::string(key), "the list is empty");
  for (std::size_t start = 0;;) {
    const std::size_t end = text.find(',', start);
    const std::string item(text.substr(start, end == std::string_view::npos ? std::string_view::npos : end - start));
    if (item.empty())
      throw InputError("", 0, std::string(key),
                       fmt::format("{} has an empty item (item {}); separate the values by single commas",
                                   shown(text), out.size() + 1));
    if (!seen.insert(item).second)
      throw InputError("", 0, std::string(key), fmt::format("{} is given twice in {}", shown(item), shown(text)));
    out.push_back(item);
    if (end == std::string_view::npos) break;
    start = end + 1;
  }
  return out;
}

std::vector<double> number_list(const NumberRule& rule, std::string_view text) {
  std::vector<double> out;
  for (const auto& item : list(rule.key, text)) {
    const double v = rule.check(std::string_view(item));
    for (double w : out)
      if (w == v)
        throw InputError("", 0, std::string(rule.key),
                         fmt::format("{} is given twice in {} (as the same number)", shown(item), shown(text)));
    out.push_back(v);
  }
  return out;
}

void at_most(std::string_view key, std::size_t n, std::size_t max, std::string_view each) {
  if (n > max)
    throw InputError("", 0, std::string(key),
                     fmt::format("{} values would be {} {}; at most {} are run by one command (split the list over "
                                 "several runs)",
                                 n, n, each, max));
}

}  // namespace chutelab::options
