#include "api/record_check.h"

#include <fmt/format.h>

#include "core/input_error.h"
#include "effects/at_condition.h"
#include "effects/registry.h"

namespace chutelab::api {

void check_records(const std::vector<std::string>& effects, const std::vector<std::string>& inputs,
                   const std::vector<Station>& stations, bool outside_range) {
  auto check = [&](const std::string& arg, const char* key) {
    const auto s = effects::parse_setting(arg, true, outside_range);
    if (s.info->kind != effects::EffectInfo::Kind::record) return;
    // A record at one condition: that condition must be one of the dataset's, and only its station is
    // corrected (an unknown name would correct nothing, silently).
    std::vector<Station> at = stations;
    if (const auto condition = effects::split_condition(s.info->name).second; !condition.empty()) {
      std::erase_if(at, [&](const Station& st) { return st.condition != condition; });
      if (at.empty()) {
        std::vector<std::string> names;
        for (const auto& st : stations) names.push_back(st.condition);
        throw InputError("", 0, key,
                         fmt::format("'{}': no condition is named {} (the conditions: {})", arg, condition,
                                     fmt::join(names, ", ")));
      }
    }
    if (!effects::stated_anywhere(*s.info, at))
      throw InputError("", 0, key,
                       fmt::format("'{}': no condition states a {}, so there is no record to correct (where none is "
                                   "given the models derive it)",
                                   arg, s.info->limits.what));
    if (s.value)
      if (const std::string why = effects::impossible_at(*s.info, *s.value, at); !why.empty())
        throw InputError("", 0, key, fmt::format("'{}': {}", arg, why));
  };
  for (const auto& a : effects) check(a, "effect");
  for (const auto& a : inputs) check(a, "input");
}

}  // namespace chutelab::api
