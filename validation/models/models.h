#pragma once
// Factories of the built-in models; the registry in model.cpp lists them.
#include "analytical/transfer_station.h"
#include "validation/model.h"

namespace chutelab::validation {

ModelPtr make_korzen_model();
ModelPtr make_booth_cema_model();

// A streamline from release to where it meets the plate line (or 1 s of flight), for pictures.
Curve streamline_curve(const analytical::TransferAnalysis& a, analytical::Streamline s,
                       std::string name);

}  // namespace chutelab::validation
