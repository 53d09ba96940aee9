#pragma once
// A recorded input wrong at one condition alone (the plate moved for one test, a load cell re-zeroed
// between two): the record's candidate restricted to that condition. Every record of the library has
// such a twin per condition; the diagnosis fits them like any candidate, named "input@condition".
#include <string>
#include <utility>

#include "effects/registry.h"

namespace chutelab::effects {

// The candidate of `record`'s error at `condition` alone: the same strength, unit and plausible
// error, acting where the station is that condition (analytical::Effect::acts_at).
EffectInfo at_condition(const EffectInfo& record, const std::string& condition);

// "plate_distance@V4-41" -> {"plate_distance", "V4-41"}; a library name -> {name, ""}.
std::pair<std::string, std::string> split_condition(const std::string& name);

// A candidate by its name: a library effect, or a record at one condition, made on first use and
// kept for the process (it is a pure function of its name). Null for an unknown name.
const EffectInfo* find_candidate(const std::string& name);

}  // namespace chutelab::effects
