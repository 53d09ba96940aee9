#pragma once
// How the registry's expensive models are made: the "dem" and "liggghts" models' configurations,
// given explicitly to make_models (validation/model.h) by whoever builds the model list (the
// library's validate and diagnose, api/). Nothing is read from process state: two calls with
// different settings make two differently configured models.
#include "validation/models/dem_model.h"
#include "validation/models/liggghts_model.h"

namespace chutelab::validation {

struct ModelSettings {
  DemModelConfig dem;            // "dem"
  LiggghtsModelConfig liggghts;  // "liggghts" (its own copy of the DEM's quality, cache, ...)
};

}  // namespace chutelab::validation
