// belt_speed: the belt ran at another speed than the record says.
//
// The record: V_b, from the drive's setting or nameplate. Strength: (V_true / V_recorded - 1) in
// %. Range -20 to +20 %. Default plausible error 2 % (a drive under load slips; a VFD's set point is
// not the speed). Unlike belt_slip, which slows the material against a belt running at V_b, the
// whole belt and its load run at V_true: the layer is as much thinner as continuity asks.
// DEM: honoured (the belt runs at V_true).
#include "effects/recorded_input.h"
#include "effects/registry.h"

namespace chutelab::effects {
namespace {

EffectInfo info() {
  EffectInfo e{"belt_speed", "error", "%", "record",
               "V_true = (1 + e) V_recorded: the stream leaves faster or slower, thinner or thicker.",
               "",
               0.0, -20.0, 20.0, 5.0,
               {},
               "a tachometer on the belt or a timed mark over a measured length"};
  set_record(e, [](Station& s, double x) { s.belt_speed *= 1.0 + x * kPercent; },
             {"belt speed", "m/s", 1.0, 0.0, 50.0, true, [](const Station& s) { return std::optional<double>(s.belt_speed); }});
  e.per_condition = true;
  e.prior_width = 2.0;
  e.input = "belt_speed";
  e.width_in_unit = relative_width([](const Station& s) { return s.belt_speed; });
  return e;
}

const Registration registration(info());

}  // namespace
}  // namespace chutelab::effects
