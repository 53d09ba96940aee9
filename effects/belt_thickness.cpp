// belt_thickness: the belt is thicker or thinner than the record says.
//
// The record: t_b, the belt's thickness. Strength: t_true - t_recorded in mm. Range -10 to +20 mm;
// the belt as really built keeps the reader's range of t_b (0 to 200 mm): a belt thinner than
// nothing has no answer, so a fit steps back and a value given is refused. Default
// plausible error 2 mm (a nominal catalogue value; top covers wear). Same signature as half a
// pulley diameter error (R_b = D/2 + t_b).
// DEM: honoured.
#include "effects/recorded_input.h"
#include "effects/registry.h"

namespace chutelab::effects {
namespace {

EffectInfo info() {
  EffectInfo e{"belt_thickness", "offset", "mm", "record",
               "t_true = t_recorded + dt: the discharge radius R_b = D/2 + t_b grows by dt.",
               "",
               0.0, -10.0, 20.0, 5.0,
               {},
               "a thickness gauge on the belt's edge"};
  set_record(e, [](Station& s, double x) { s.belt.belt_thickness += x * kMm; },
             rig_field_limits("belt_thickness_mm", "belt thickness", "mm", [](const Station& s) { return s.belt.belt_thickness; }));
  e.prior_width = 2.0;
  e.input = "belt.belt_thickness_mm";
  e.width_in_unit = offset_width(kMm);
  return e;
}

const Registration registration(info());

}  // namespace
}  // namespace chutelab::effects
