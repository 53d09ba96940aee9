#pragma once
// The effect library (effects/registry.h) as the front ends list it: api-owned entries, so that the
// designer's page, which links no fits, lists the effects through the same door as Python.
#include <string>
#include <vector>

namespace chutelab::api {

struct EffectEntry {
  std::string name, parameter, unit, stage;  // unit: the strength's at the boundary ("" = none)
  bool record = false;                       // a recorded input that may be wrong, else physics
  double neutral = 0.0, lower = 0.0, upper = 0.0, typical = 0.0;
  std::string physics, source;
};
std::vector<EffectEntry> effect_library();

}  // namespace chutelab::api
