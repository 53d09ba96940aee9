#include "analytical/stream_catch.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace chutelab::analytical {

StreamCatch stream_catch(const TransferAnalysis& a) {
  const double height = a.plate.height;
  // (e, distance below the top edge where the layer crosses the plate line), by height.
  std::array<std::pair<double, double>, 4> layer;
  for (std::size_t i = 0; i < kAllStreamlines.size(); ++i) {
    const auto& l = a.line(kAllStreamlines[i]);
    layer[i] = {l.height_above_belt, l.hit ? l.hit->along : height};
  }
  std::sort(layer.begin(), layer.end());
  const double total = a.load.area;
  auto mass_below = [&](double e) { return load_area_below(a.station.belt, a.load, e) / total; };

  StreamCatch c;
  c.caught = c.over_top = c.past_foot = 0.0;
  // Each piece between two flown layers: the crossing is linear in e, so the layers above the top
  // edge, on the plate and below the foot are three intervals of e.
  for (std::size_t i = 0; i + 1 < layer.size(); ++i) {
    const double e0 = layer[i].first, s0 = layer[i].second;
    const double e1 = layer[i + 1].first, s1 = layer[i + 1].second;
    if (!(e1 > e0)) continue;
    const double m0 = mass_below(e0), m1 = mass_below(e1);
    if (s0 == s1) {
      (s0 < 0.0 ? c.over_top : s0 > height ? c.past_foot : c.caught) += m1 - m0;
      continue;
    }
    // Going up the layers the crossing moves from s0 to s1; the edges cut the piece at these e.
    auto layer_at = [&](double s) { return e0 + (e1 - e0) * (s - s0) / (s1 - s0); };
    const double at_top = std::clamp(layer_at(0.0), e0, e1), at_foot = std::clamp(layer_at(height), e0, e1);
    const bool rising = s1 < s0;  // higher layers cross higher on the face (the usual case)
    const double lo_on = rising ? at_foot : at_top, hi_on = rising ? at_top : at_foot;
    const double on = std::max(0.0, mass_below(hi_on) - mass_below(lo_on));
    const double above = rising ? m1 - mass_below(at_top) : mass_below(at_top) - m0;
    const double below = rising ? mass_below(at_foot) - m0 : m1 - mass_below(at_foot);
    c.caught += on;
    c.over_top += std::max(0.0, above);
    c.past_foot += std::max(0.0, below);
    if ((s0 < 0.0) != (s1 < 0.0)) c.top_edge_layer = at_top;
    if ((s0 > height) != (s1 > height)) c.foot_edge_layer = at_foot;
  }
  // The pieces' shares sum to one up to rounding; a stream wholly on the plate is exactly whole.
  if (c.over_top <= 1e-12 && c.past_foot <= 1e-12) {
    c.caught = 1.0;
    c.over_top = c.past_foot = 0.0;
  }
  c.normal_force = c.caught * a.korzen.normal_force;
  c.shear_force = c.caught * a.korzen.shear_force;
  return c;
}

}  // namespace chutelab::analytical
