// plate_distance: the plate stood at another distance from the pulley than the record says.
//
// The record: Z, the horizontal distance of the plate face's top edge from the pulley axis. Plates
// are set with a tape against a drawing; a rig rebuilt between test series keeps the old drawing.
// Strength: Z_true - Z_recorded in mm. Range -150 to +150 mm (beyond it the stream misses most
// plates). Default plausible error (one sigma) 10 mm: a taped distance, ±30 mm at three sigma.
// Every quantity that depends on where the stream strikes moves: the impact point, V_p, and with
// them R_n, R_s; the free trajectory does not.
// DEM: honoured (the plate is placed at Z_true).
#include "effects/recorded_input.h"
#include "effects/registry.h"

namespace chutelab::effects {
namespace {

EffectInfo info() {
  EffectInfo e{"plate_distance", "offset", "mm", "record",
               "Z_true = Z_recorded + dZ: the stream strikes the plate further along its flight (lower, faster).",
               "",
               0.0, -150.0, 150.0, 25.0,
               {},
               "a tape or laser distance from the pulley axis to the plate face at its top edge"};
  set_record(e, [](Station& s, double x) { s.plate_distance += x * kMm; },
             {"plate distance", "mm", kMm, 0.0, 1e5, true, [](const Station& s) { return std::optional<double>(s.plate_distance); }});
  e.per_condition = true;
  e.prior_width = 10.0;
  e.input = "plate_distance";
  e.width_in_unit = offset_width(kMm);
  return e;
}

const Registration registration(info());

}  // namespace
}  // namespace chutelab::effects
