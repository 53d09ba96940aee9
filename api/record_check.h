#pragma once
// Corrected records checked before any run. Apart from api/effects.h because the designer's
// WebAssembly page (app/design) links the estimate, which calls it, and not the fitting machinery.
#include <string>
#include <vector>

#include "core/rig.h"

namespace chutelab::api {

// Records among the effects and inputs given (NAME=VALUE|fit) checked against the stations before
// any run: a value that leaves a station's input outside its physical limits (a belt -5 mm thick)
// is refused, and so is any record that no station states (a stream thickness where no condition
// gives one: there is nothing to correct). InputError with the key "input" for an argument of
// `inputs`, "effect" for one of `effects`; `outside_range` as effects::parse_setting.
void check_records(const std::vector<std::string>& effects, const std::vector<std::string>& inputs,
                   const std::vector<Station>& stations, bool outside_range = false);

}  // namespace chutelab::api
