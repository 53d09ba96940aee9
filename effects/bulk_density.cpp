// bulk_density: the material's bulk density on the belt differs from the record.
//
// The record: rho_bl. Strength: (rho_true / rho_recorded - 1) in %. Range -30 to +30 %. Default
// plausible error 5 % (a loose-poured test against a belt-vibrated layer). With the stream's
// thickness from continuity, the layer is as much thinner as the density is higher: it moves the
// stream's limits and the Korzen streamline, not the forces.
// DEM: not an input (the DEM's layer forms from its particles): the signature is the analytical
// chain's.
#include "effects/recorded_input.h"
#include "effects/registry.h"

namespace chutelab::effects {
namespace {

EffectInfo info() {
  EffectInfo e{"bulk_density", "error", "%", "record",
               "rho_true = (1 + e) rho_recorded: h_b from continuity shrinks by 1 / (1 + e).",
               "",
               0.0, -30.0, 30.0, 10.0,
               {},
               "a weighed sample of the layer cut from a stopped belt (or a bulk density test of the material as it ran)"};
  set_record(e, [](Station& s, double x) { s.material.bulk_density *= 1.0 + x * kPercent; },
             rig_field_limits("bulk_density_kgm3", "bulk density", "kg/m³", [](const Station& s) { return s.material.bulk_density; }));
  e.prior_width = 5.0;
  e.input = "material.bulk_density_kgm3";
  e.width_in_unit = relative_width([](const Station& s) { return s.material.bulk_density; });
  return e;
}

const Registration registration(info());

}  // namespace
}  // namespace chutelab::effects
