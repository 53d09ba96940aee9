#pragma once
// The library of candidate physical effects (DESIGN.md §4). Each effect is one file in effects/
// that describes its physics and registers itself with one line; nothing else needs to change.
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "analytical/effect.h"

namespace chutelab::effects {

struct EffectInfo {
  std::string name;          // DESIGN.md §4 name, e.g. "air_drag"
  std::string parameter;     // name of the strength parameter with unit, e.g. "drag_coefficient"
  std::string unit;          // unit of the parameter at the boundary ("" = dimensionless)
  std::string stage;         // where it hooks in: discharge, flight, plate, measurement, ...
  std::string physics;       // the equation and its meaning, one paragraph
  std::string source;        // where the physics comes from
  double neutral = 0.0;      // the value that switches the effect off
  double lower = 0.0;        // physical range; a fit stays inside it
  double upper = 0.0;
  double typical = 0.0;      // a realistic non-neutral strength (for synthetic tests and docs)
  std::function<std::shared_ptr<const analytical::Effect>(double)> make;
  // An independent measurement that confirms or rules the effect out, for when the data at hand
  // cannot tell it from another candidate ("" = none beyond chutelab's vocabulary).
  std::string check = {};
};

// How far a fit may go past the physical range when it asks what strength the data want, whatever
// physics allows (a negative drag coefficient: particles faster than ballistic): the physical range
// widened by its own span on each side. The effects' formulas stay defined there; where the
// analytical chain has no answer, a trial gives a large misfit, as inside the range.
struct Range {
  double lower = 0.0, upper = 0.0;
};
Range extended_range(const EffectInfo& e);
bool in_physical_range(const EffectInfo& e, double strength);

// All registered effects, sorted by name.
const std::vector<EffectInfo>& library();
const EffectInfo* find(const std::string& name);

// Called once per effect file through a static Registration object.
struct Registration {
  explicit Registration(EffectInfo info);
};

// "NAME=VALUE" or "NAME=fit" (fit only where allow_fit); throws InputError naming the flag.
struct EffectSetting {
  const EffectInfo* info = nullptr;
  std::optional<double> value;  // absent: fit to the data
};
// `outside_range`: strengths beyond the physical range (within extended_range) are accepted: only
// to make test data that break physics on purpose.
EffectSetting parse_setting(const std::string& text, bool allow_fit, bool outside_range = false);
analytical::EffectList instantiate(const std::vector<EffectSetting>& fixed);

}  // namespace chutelab::effects
