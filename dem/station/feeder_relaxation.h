#pragma once
// Feeder relaxation: in the feed zone, each particle's velocity is relaxed towards the belt's,
//   F = m k (V_b t - v)   for the components along the belt surface (t: direction of travel),
//   F_n = -m k v_n        for the component normal to the belt, only while moving away from it,
// with rate k (1/s). It stands in for the loading chute and skirts of a real conveyor: particles
// dropped on the belt come to rest on it within a few 1/k instead of bouncing and sliding for the
// whole belt length, so a short belt delivers a quiet, settled layer. The LIGGGHTS virtual rig
// relaxed the whole velocity (rate 50 1/s) up to 50 mm past the insertion face
// (datasets/liggghts-rig/README.md); relaxing the vertical fall as well holds falling particles at
// g/k = 0.2 m/s, so many were still in the air where the relaxation ended and bounced on the free
// belt. Here the fall is free and only rebounds are damped, and the zone reaches 50 mm past where
// the last inserted particles land. Downstream of it the layer is carried by belt friction alone
// (tests/dem_station check that it reaches the pulley at belt speed). A dataset whose feeder did
// otherwise declares it ([dem.feed]: relax_components = "all", relax_end = "face"), so that the
// DEM runs the experiment as it was run.
#include <cstddef>
#include <vector>

#include "dem/particles.h"
#include "dem/station/frames.h"

namespace chutelab::dem::station {

struct FeederRelaxation {
  BeltFrame belt;
  double belt_speed = 0.0;   // m/s
  double rate = 0.0;         // k, 1/s
  double s_begin = 0.0;      // belt coordinate range where it acts, m
  double s_end = 0.0;
  double h_max = 0.0;        // and only below this height above the belt, m
  bool all_components = false;  // relax the fall too (a dataset's feeder, [dem.feed] relax_components)

  // Adds to force[begin, end).
  void add(const Particles& p, std::size_t begin, std::size_t end, std::vector<Vec3>& force) const {
    if (!(rate > 0.0)) return;
    const Vec3 vb = belt_speed * belt.along;
    for (std::size_t i = begin; i < end; ++i) {
      const double s = belt.s(p.x[i]);
      if (s < s_begin || s > s_end || belt.h(p.x[i]) > h_max) continue;
      Vec3 dv = vb - p.v[i];
      const double vn = p.v[i].dot(belt.up);
      if (!all_components) dv += (vn < 0.0 ? vn : 0.0) * belt.up;  // a falling particle keeps its fall
      force[i] += (p.mass[i] * rate) * dv;
    }
  }
};

}  // namespace chutelab::dem::station
