#include "effects/registry.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fmt/format.h>

#include "core/input_error.h"
#include "core/number.h"
#include "effects/at_condition.h"

namespace chutelab::effects {
namespace {
std::vector<EffectInfo>& mutable_library() {
  static std::vector<EffectInfo> all;  // constructed on first use: safe from any static initialiser
  return all;
}
}  // namespace

Registration::Registration(EffectInfo info) {
  auto& all = mutable_library();
  all.push_back(std::move(info));
  std::sort(all.begin(), all.end(), [](const auto& a, const auto& b) { return a.name < b.name; });
}

const std::vector<EffectInfo>& library() { return mutable_library(); }

const EffectInfo* find(const std::string& name) {
  for (const auto& e : library())
    if (e.name == name) return &e;
  return nullptr;
}

Range extended_range(const EffectInfo& e) {
  const double span = e.upper - e.lower;
  // The sum rounded to 12 significant digits and read back: the nearest double to the decimal a
  // reader computes, so that the stated end is inside.
  auto decimal = [](double v) { return parse_number(fmt::format("{:.12g}", v)).value_or(v); };
  return {decimal(e.lower - span), decimal(e.upper + span)};
}

bool in_physical_range(const EffectInfo& e, double strength) { return strength >= e.lower && strength <= e.upper; }

EffectSetting parse_setting(const std::string& text, bool allow_fit, bool outside_range, const std::string& key) {
  const auto eq = text.find('=');
  const std::string name = text.substr(0, eq);
  // A recorded input may be given at one condition alone ("plate_distance@V4-41"), as the diagnosis
  // names it; which conditions a dataset has is checked against its stations (api/record_check.h).
  const auto [base, condition] = split_condition(name);
  if (!condition.empty())
    if (const EffectInfo* b = find(base); b && b->kind != EffectInfo::Kind::record)
      throw InputError("", 0, key,
                       fmt::format("'{}': {} is a physical effect; only a recorded input can be wrong at one condition "
                                   "alone (NAME@CONDITION)",
                                   text, base));
  const EffectInfo* info = find_candidate(name);
  if (!info) {
    std::vector<std::string> names;
    for (const auto& e : library()) names.push_back(e.name);
    throw InputError("", 0, key,
                     fmt::format("unknown effect '{}' (known: {})", name, fmt::join(names, ", ")));
  }
  if (eq == std::string::npos)
    throw InputError("", 0, key,
                     fmt::format("'{}' needs a value: {}=VALUE{}", text, name,
                                 allow_fit ? " or " + name + "=fit" : ""));
  const std::string value = text.substr(eq + 1);
  if (value == "fit") {
    if (!allow_fit)
      throw InputError("", 0, key,
                       fmt::format("'{}': fitting needs measurements; give a value here", text));
    return {info, std::nullopt};
  }
  const auto parsed = parse_number(value);
  const double v = parsed.value_or(0.0);
  if (!parsed || !std::isfinite(v))
    throw InputError("", 0, key, fmt::format("'{}': '{}' is not a number", text, value));
  if (outside_range) {
    const Range r = extended_range(*info);
    if (v < r.lower || v > r.upper)
      throw InputError("", 0, key,
                       fmt::format("'{}': {} must lie in [{}, {}] {} (its physical range [{}, {}] widened by its span on each side)",
                                   text, info->parameter, r.lower, r.upper, info->unit, info->lower, info->upper));
  } else if (!in_physical_range(*info, v)) {
    throw InputError("", 0, key,
                     fmt::format("'{}': {} must lie in its physical range [{}, {}] {}", text,
                                 info->parameter, info->lower, info->upper, info->unit));
  }
  return {info, v};
}

std::string RecordLimits::problem(double si, double recorded_si) const {
  const double v = si / to_si;
  if (v <= upper && (open_below ? v > lower : v >= lower)) return "";
  return fmt::format("the {} as really built would be {:.4g} {} (recorded {:.4g} {}), outside its physical range {}{}, {}] {}",
                     what, v, unit, recorded_si / to_si, unit, open_below ? "(" : "[", lower, upper, unit);
}

std::string impossible_at(const EffectInfo& e, double strength, const std::vector<Station>& stations) {
  const auto effect = e.make(strength);
  for (const Station& st : stations) try {
      Station s = st;
      effect->adjust_station(s);
    } catch (const InputError& err) {
      return fmt::format("at {}: {}", st.condition, err.problem());
    }
  return "";
}

bool stated_anywhere(const EffectInfo& e, const std::vector<Station>& stations) {
  if (!e.limits.value) return true;
  return std::any_of(stations.begin(), stations.end(), [&](const Station& s) { return e.limits.value(s).has_value(); });
}

analytical::EffectList instantiate(const std::vector<EffectSetting>& fixed) {
  analytical::EffectList out;
  for (const auto& s : fixed)
    if (s.value) out.push_back(s.info->make(*s.value));
  return out;
}

}  // namespace chutelab::effects
