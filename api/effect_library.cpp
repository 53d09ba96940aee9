#include "api/effect_library.h"

#include "effects/registry.h"

namespace chutelab::api {

std::vector<EffectEntry> effect_library() {
  std::vector<EffectEntry> out;
  for (const auto& e : effects::library())
    out.push_back({e.name, e.parameter, e.unit, e.stage, e.kind == effects::EffectInfo::Kind::record, e.neutral,
                   e.lower, e.upper, e.typical, e.physics, e.source});
  return out;
}

}  // namespace chutelab::api
