#include "analytical/impact_zone.h"

#include <algorithm>
#include <cmath>

namespace chutelab::analytical {

ImpactZone impact_zone(const TransferAnalysis& a) {
  const PlateLine& p = a.plate;
  // A limit that never meets the plate line fell short of it below the foot (the only way a stream
  // that reaches the plate with its centre can miss the line with an edge).
  auto along = [&](Streamline s) {
    const auto& h = a.line(s).hit;
    return h ? h->along : p.height;
  };
  const double centre = a.line(Streamline::cema_centroid).hit->along;
  double lo = std::min({along(Streamline::upper), along(Streamline::lower), centre});
  double hi = std::max({along(Streamline::upper), along(Streamline::lower), centre});
  ImpactZone z;
  z.top_clipped = lo < 0.0;
  z.bottom_clipped = hi > p.height;
  lo = std::clamp(lo, 0.0, p.height);
  hi = std::clamp(hi, 0.0, p.height);
  // A stream thinner than nothing cannot load a line: keep a band of at least one particle's
  // diameter so the mean pressure stays finite when h_b -> 0.
  // (A setup for the analytical models alone may leave the particle's size out: then 1 mm.)
  const double d = a.station.material.particle_diameter;
  const double min_band = std::isfinite(d) ? std::max(d, 1e-3) : 1e-3;
  if (hi - lo < min_band) {
    const double mid = 0.5 * (lo + hi);
    lo = std::clamp(mid - 0.5 * min_band, 0.0, std::max(0.0, p.height - min_band));
    hi = std::min(p.height, lo + min_band);
  }
  z.top_along = lo;
  z.bottom_along = hi;
  z.top_y = (p.top + lo * p.down()).y();
  z.bottom_y = (p.top + hi * p.down()).y();
  z.centroid_y = a.line(Streamline::cema_centroid).hit->point.position.y();
  const double w = a.station.belt.loaded_width > 0.0 ? a.station.belt.loaded_width : a.station.belt.belt_width;
  z.width = a.station.plate.width > 0.0 ? std::min(w, a.station.plate.width) : w;
  z.area = z.length() * z.width;
  // Only what meets the plate loads it: a stream partly over the top edge leaves a shorter band and
  // a smaller force, not the whole stream's force on the part of the band that is left.
  z.caught = stream_catch(a);
  z.mean_pressure = z.caught.normal_force / z.area;
  z.mean_shear_stress = z.caught.shear_force / z.area;
  return z;
}

}  // namespace chutelab::analytical
