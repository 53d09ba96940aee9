#pragma once
// Which setup keys a model reads. The analytical models (Booth/CEMA, Korzen) read the rig's
// geometry, the bulk density and the wall friction; the contact model's material values are the
// DEM's alone, so a setup without them serves every analytical model and the DEM asks for them,
// every missing one in one message, before it runs (an absent one is NaN in the Setup).
#include <string>
#include <string_view>
#include <vector>

#include "core/rig.h"

namespace chutelab {

// A key only the DEM reads (and air drag, for the particles' size and density): optional in
// setup.toml, required by the DEM.
bool read_by_dem_only(const RigField& f);

// The keys of read_by_dem_only() the station has no value of, as "material.youngs_modulus_Pa".
std::vector<std::string> missing_dem_keys(const Station& station);

// Throws InputError naming `file` (setup.toml; may be empty) and every missing key in one message
// when the station lacks a key the DEM reads; `who` names the run ("the DEM", "LIGGGHTS").
void require_dem_keys(const Station& station, std::string_view file = "setup.toml", std::string_view who = "the DEM");

// "" when every station gives the particles' size and density; else why air drag (a force per unit
// mass of one particle) cannot be tried on this rig, for a diagnosis to say before it ranks without it.
std::string air_drag_unavailable(const std::vector<Station>& stations);

}  // namespace chutelab
