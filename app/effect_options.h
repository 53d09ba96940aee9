#pragma once
// --effect NAME=VALUE|fit for validate: fixed strengths as given, "fit" ones calibrated on the
// dataset (jointly, with the fixed ones applied).
#include <string>
#include <vector>

#include "reports/report.h"
#include "validation/dataset.h"
#include "validation/model.h"

namespace chutelab::app {

struct AppliedEffects {
  analytical::EffectList effects;
  std::vector<std::string> labels;  // "air_drag=0.61 (fitted)"
  std::vector<std::string> notes;
};

AppliedEffects resolve_effects(const std::vector<std::string>& args, const validation::Dataset& d,
                               const std::vector<validation::ModelPtr>& models,
                               std::vector<reports::EffectDescription>& described);

// --input NAME=VALUE|fit: a recorded input's error (effects/registry.h, Kind::record), given as an
// effect is; the arguments of --effect followed by those of --input. An --input that names a
// physical effect is refused, naming the flag and the recorded inputs there are.
std::vector<std::string> effects_and_inputs(const std::vector<std::string>& effects,
                                            const std::vector<std::string>& inputs);

// Models in registry order (where they overlap, fits take each quantity from the first).
std::vector<validation::ModelPtr> in_registry_order(const std::vector<validation::ModelPtr>& models);

}  // namespace chutelab::app
