#include "core/option_check.h"

#include <fmt/format.h>

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
  if (has_lo && has_hi)
    range = fmt::format(" in {}{}, {}{}", lo_open ? "(" : "[", num(lo), num(hi), hi_open ? ")" : "]");
  else if (has_lo)
    range = fmt::format(" {} {}", lo_open ? ">" : ">=", num(lo));
  else if (has_hi)
    range = fmt::format(" {} {}", hi_open ? "<" : "<=", num(hi));
  std::string out = what + range;
  if (!unit.empty()) out.append(" ").append(unit);
  return out;
}

double NumberRule::check(double v) const {
  const bool ok = std::isfinite(v) && (!whole || v == std::floor(v)) && (lo_open ? v > lo : v >= lo) &&
                  (hi_open ? v < hi : v <= hi);
  if (!ok) throw InputError("", 0, std::string(flag), fmt::format("must be {}, got {}", describe(), num(v)));
  return v;
}

double NumberRule::check(std::string_view typed) const {
  const auto v = parse_number(typed);
  if (!v || !std::isfinite(*v))
    throw InputError("", 0, std::string(flag), fmt::format("must be {}, got {}", describe(), shown(typed)));
  try {
    return check(*v);
  } catch (const InputError&) {
    throw InputError("", 0, std::string(flag), fmt::format("must be {}, got {}", describe(), shown(typed)));
  }
}

void non_empty(std::string_view flag, std::string_view value) {
  if (value.empty())
    throw InputError("", 0, std::string(flag), "is empty; give a value or leave the option out");
}

std::vector<std::string> list(std::string_view flag, std::string_view text) {
  std::vector<std::string> out;
  std::set<std::string> seen;
  if (text.empty()) throw InputError("", 0, std::string(flag), "the list is empty");
  for (std::size_t start = 0;;) {
    const std::size_t end = text.find(',', start);
    const std::string item(text.substr(start, end == std::string_view::npos ? std::string_view::npos : end - start));
    if (item.empty())
      throw InputError("", 0, std::string(flag),
                       fmt::format("{} has an empty item (item {}); separate the values by single commas",
                                   shown(text), out.size() + 1));
    if (!seen.insert(item).second)
      throw InputError("", 0, std::string(flag), fmt::format("{} is given twice in {}", shown(item), shown(text)));
    out.push_back(item);
    if (end == std::string_view::npos) break;
    start = end + 1;
  }
  return out;
}

std::vector<double> number_list(const NumberRule& rule, std::string_view text) {
  std::vector<double> out;
  for (const auto& item : list(rule.flag, text)) {
    const double v = rule.check(std::string_view(item));
    for (double w : out)
      if (w == v)
        throw InputError("", 0, std::string(rule.flag),
                         fmt::format("{} is given twice in {} (as the same number)", shown(item), shown(text)));
    out.push_back(v);
  }
  return out;
}

void at_most(std::string_view flag, std::size_t n, std::size_t max, std::string_view each) {
  if (n > max)
    throw InputError("", 0, std::string(flag),
                     fmt::format("{} values would be {} {}; at most {} are run by one command (split the list over "
                                 "several runs)",
                                 n, n, each, max));
}

}  // namespace chutelab::options
