#include "api/record_check.h"

#include <fmt/format.h>

#include "core/input_error.h"
#include "effects/registry.h"

namespace chutelab::api {

void check_records(const std::vector<std::string>& effects, const std::vector<std::string>& inputs,
                   const std::vector<Station>& stations, bool outside_range) {
  auto check = [&](const std::string& arg, const char* key) {
    const auto s = effects::parse_setting(arg, true, outside_range);
    if (s.info->kind != effects::EffectInfo::Kind::record) return;
    if (!effects::stated_anywhere(*s.info, stations))
      throw InputError("", 0, key,
                       fmt::format("'{}': no condition states a {}, so there is no record to correct (where none is "
                                   "given the models derive it)",
                                   arg, s.info->limits.what));
    if (s.value)
      if (const std::string why = effects::impossible_at(*s.info, *s.value, stations); !why.empty())
        throw InputError("", 0, key, fmt::format("'{}': {}", arg, why));
  };
  for (const auto& a : effects) check(a, "effect");
  for (const auto& a : inputs) check(a, "input");
}

}  // namespace chutelab::api
