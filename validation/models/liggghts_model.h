#pragma once
// LIGGGHTS-PUBLIC as a harness model, "liggghts" in --models (dem/liggghts): the same station, the
// same sensors and steady-state rule as "dem", another engine. An expensive model: each condition
// is one LIGGGHTS run (minutes to hours), cached like the DEM's by every input that matters plus the
// deck text, its meshes, the LIGGGHTS version string and the launcher.
//
// Effects act as for "dem" (dem_model.h) except body forces in flight and belt adhesion, which the
// deck does not write (noted in the prediction).
#include <string>

#include "validation/models/dem_model.h"

namespace chutelab::validation {

struct LiggghtsModelConfig {
  DemModelConfig dem;        // quality, [dem] table, cache, progress, output folder
  int ranks = 1;             // mpirun -n ranks liggghts
  std::string command;       // "" = "mpirun -n <ranks> liggghts"; e.g. "srun liggghts" on a cluster
  double sim_time = 0.0;     // s simulated per condition; 0 = the quality's max_time
};

// The registry's "liggghts" model is made by make_model with ModelSettings::liggghts.
ModelPtr make_liggghts_model(const LiggghtsModelConfig& c);

}  // namespace chutelab::validation
