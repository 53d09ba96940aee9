#pragma once
// Effects given as NAME=VALUE|fit ("effect" and "input" options of validate, diagnose's winner
// with add_missing): fixed strengths as given, "fit" ones calibrated on the dataset (jointly, with
// the fixed ones applied).
#include <string>
#include <vector>

#include "api/effect_library.h"
#include "reports/report.h"
#include "validation/diagnosis.h"
#include "validation/dataset.h"
#include "validation/model.h"

namespace chutelab::api {

struct AppliedEffects {
  analytical::EffectList effects;
  std::vector<std::string> labels;  // "air_drag=0.61 (fitted)"
  std::vector<std::string> notes;
};

// The arguments parsed: fixed strengths and those to fit. Throws InputError (key "effect") for an
// unknown effect, a bad value, one given twice or more to fit at once than a fit can take.
struct ParsedEffects {
  std::vector<effects::EffectSetting> fixed, to_fit;
};
ParsedEffects parse_effects(const std::vector<std::string>& args);

// `also`: effects applied with the fixed ones while fitting (not returned): the diagnosis's
// recommended explanation when add_missing adds it beside inputs to fit.
AppliedEffects resolve_effects(const std::vector<std::string>& args, const validation::Dataset& d,
                               const std::vector<validation::ModelPtr>& models,
                               std::vector<reports::EffectDescription>& described,
                               const analytical::EffectList& also = {});

// The diagnosis's recommended explanation (add_missing) at the strengths its verdict states: the
// diagnosis's own fit, under its noise model, so that readings it left out and quantities it set
// aside as no effect's (a model-form error) do not pull the strengths. A refit of every point as
// stated can land on the other side of the record from what the verdict says. Effects in `skip`
// (given by the caller as well) are left to the caller's setting.
AppliedEffects diagnosed_effects(const validation::DiagnosisResult& diagnosis,
                                 const std::vector<std::string>& skip,
                                 std::vector<reports::EffectDescription>& described);

// Inputs NAME=VALUE|fit: a recorded input's error (effects/registry.h, Kind::record), given as an
// effect is; the effects followed by the inputs. An input that names a physical effect is refused
// (key "input"), naming the recorded inputs there are; so is any other problem of an input (a value
// that is no number, out of range, `fit` where nothing is fitted, given twice), checked here as
// effects::parse_setting(text, allow_fit, outside_range) checks an effect.
std::vector<std::string> effects_and_inputs(const std::vector<std::string>& effects,
                                            const std::vector<std::string>& inputs, bool allow_fit = true,
                                            bool outside_range = false);

// Models in registry order (where they overlap, fits take each quantity from the first).
std::vector<validation::ModelPtr> in_registry_order(const std::vector<validation::ModelPtr>& models);

}  // namespace chutelab::api
