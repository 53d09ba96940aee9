// stream_thickness: the measured thickness of the layer on the belt is off.
//
// The record: h_b, where a condition states it (otherwise it follows from continuity and this
// candidate changes nothing: a value or fit given for it where no condition states one is refused). Strength: h_true - h_recorded in mm. Range -30 to +30 mm. Default
// plausible error 3 mm (a ruler against a moving, uneven surface). It sets the stream's limits and
// the Korzen streamline (0.5 h_b).
// DEM: not an input (the DEM's layer forms from the feed): the signature is the analytical chain's.
#include "effects/recorded_input.h"
#include "effects/registry.h"

namespace chutelab::effects {
namespace {

EffectInfo info() {
  EffectInfo e{"stream_thickness", "offset", "mm", "record",
               "h_true = h_recorded + dh, where h_b is stated: the stream's upper limit and centre move.",
               "",
               0.0, -30.0, 30.0, 8.0,
               {},
               "a profile gauge or a photograph of the layer against a scale"};
  set_record(e, [](Station& s, double x) { if (s.stream_thickness) *s.stream_thickness += x * kMm; },
             {"stream thickness", "mm", kMm, 0.0, 1e4, true, [](const Station& s) { return s.stream_thickness; }});
  e.per_condition = true;
  e.prior_width = 3.0;
  e.input = "stream_thickness";
  e.width_in_unit = offset_width(kMm);
  return e;
}

const Registration registration(info());

}  // namespace
}  // namespace chutelab::effects
