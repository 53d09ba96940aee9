#pragma once
// Factories of the built-in models; the registry in model.cpp lists them.
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "analytical/transfer_station.h"
#include "validation/model.h"

namespace chutelab::validation {

ModelPtr make_korzen_model();
ModelPtr make_booth_cema_model();

// The cheap (analytical) models in registry order: what `estimate` and the designer's page run.
// They need nothing but the analytical chain, so the page's WebAssembly build links only these.
using ModelFactory = std::pair<std::string, std::function<ModelPtr()>>;
const std::vector<ModelFactory>& analytical_model_registry();
std::vector<ModelPtr> analytical_models();

// A streamline from release to where it meets the plate line (or 1 s of flight), for pictures.
Curve streamline_curve(const analytical::TransferAnalysis& a, analytical::Streamline s,
                       std::string name);

}  // namespace chutelab::validation
