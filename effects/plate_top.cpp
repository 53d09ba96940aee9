// plate_top: the plate's top edge stood at another height than the record says.
//
// The record: the y of the plate's top edge relative to the pulley axis. Strength: y_true -
// y_recorded in mm. Range -150 to +150 mm. Default plausible error 10 mm (a taped height).
// It moves where on the plate the stream strikes (the impact point in plate coordinates) and, on a
// leaning plate, the distance the stream flies.
// DEM: honoured.
#include "effects/recorded_input.h"
#include "effects/registry.h"

namespace chutelab::effects {
namespace {

EffectInfo info() {
  EffectInfo e{"plate_top", "offset", "mm", "record",
               "y_top,true = y_top,recorded + dy: the plate sits higher or lower in the stream.",
               "",
               0.0, -150.0, 150.0, 25.0,
               {},
               "a tape or level from the pulley axis to the plate's top edge"};
  set_record(e, [](Station& s, double x) { s.plate_top += x * kMm; },
             {"plate top", "mm", kMm, -1e5, 1e5, false, [](const Station& s) { return std::optional<double>(s.plate_top); }});
  e.per_condition = true;
  e.prior_width = 10.0;
  e.input = "plate_top";
  e.width_in_unit = offset_width(kMm);
  return e;
}

const Registration registration(info());

}  // namespace
}  // namespace chutelab::effects
