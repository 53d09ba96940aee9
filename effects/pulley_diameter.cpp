// pulley_diameter: the head pulley's diameter differs from the record (a lagging left out).
//
// The record: D, the pulley's diameter. Strength: D_true - D_recorded in mm. Range -100 to +100
// mm. Default plausible error 5 mm (a nominal shell size; a rubber lagging adds 12-30 mm).
// The discharge radius R_b = D/2 + t_b moves the release point and the release condition (Booth's
// V^2 / (g R_b)); so does a belt thickness error of half the size, which the data cannot tell
// apart (same signature).
// DEM: honoured.
#include "effects/recorded_input.h"
#include "effects/registry.h"

namespace chutelab::effects {
namespace {

EffectInfo info() {
  EffectInfo e{"pulley_diameter", "offset", "mm", "record",
               "D_true = D_recorded + dD: the discharge radius R_b = D/2 + t_b grows by dD/2.",
               "",
               0.0, -100.0, 100.0, 25.0,
               {},
               "a tape round the lagged pulley (circumference / pi)"};
  set_record(e, [](Station& s, double x) { s.belt.pulley_diameter += x * kMm; },
             rig_field_limits("pulley_diameter_mm", "pulley diameter", "mm", [](const Station& s) { return s.belt.pulley_diameter; }));
  e.prior_width = 5.0;
  e.input = "belt.pulley_diameter_mm";
  e.width_in_unit = offset_width(kMm);
  return e;
}

const Registration registration(info());

}  // namespace
}  // namespace chutelab::effects
