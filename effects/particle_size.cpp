// particle_size: the particles are larger or smaller than the record says.
//
// The record: d_p, the particle diameter (a sieve fraction's nominal size). Strength: (d_true /
// d_recorded - 1) in %. Range -50 to +50 %. Default plausible error 10 % (a sieve fraction's
// width). The analytical chain sees the size only through a flight force (air drag); the DEM sees
// it in every contact.
// DEM: honoured.
#include "effects/recorded_input.h"
#include "effects/registry.h"

namespace chutelab::effects {
namespace {

EffectInfo info() {
  EffectInfo e{"particle_size", "error", "%", "record",
               "d_true = (1 + e) d_recorded: drag per unit mass and the DEM's packing change.",
               "",
               0.0, -50.0, 50.0, 20.0,
               {},
               "a sieve analysis of the material as it ran"};
  set_record(e, [](Station& s, double x) { s.material.particle_diameter *= 1.0 + x * kPercent; },
             rig_field_limits("particle_diameter_mm", "particle diameter", "mm", [](const Station& s) { return s.material.particle_diameter; }));
  e.prior_width = 10.0;
  e.input = "material.particle_diameter_mm";
  e.width_in_unit = relative_width([](const Station& s) { return s.material.particle_diameter; });
  return e;
}

const Registration registration(info());

}  // namespace
}  // namespace chutelab::effects
