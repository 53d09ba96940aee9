// plate_angle: the plate leaned at another angle than the record says.
//
// The record: beta, the plate's angle from vertical. Strength: beta_true - beta_recorded in
// degrees. Range -15 to +15 degrees. Default plausible error 1 degree (a plate set by eye against
// a square). The angle sets the split of the impact momentum into normal and shear (R_n, R_s) and
// the exit velocity along the face.
// DEM: honoured.
#include "core/units.h"
#include "effects/recorded_input.h"
#include "effects/registry.h"

namespace chutelab::effects {
namespace {

EffectInfo info() {
  EffectInfo e{"plate_angle", "offset", "deg", "record",
               "beta_true = beta_recorded + d_beta: the stream's momentum splits differently into R_n and R_s.",
               "",
               0.0, -15.0, 15.0, 4.0,
               {},
               "an inclinometer on the plate face"};
  set_record(e, [](Station& s, double x) { s.plate.angle += x * units::deg; },
             rig_field_limits("angle_deg", "plate angle", "deg", [](const Station& s) { return s.plate.angle; }));
  e.per_condition = true;
  e.prior_width = 1.0;
  e.input = "plate.angle_deg";
  e.width_in_unit = offset_width(units::deg);
  return e;
}

const Registration registration(info());

}  // namespace
}  // namespace chutelab::effects
