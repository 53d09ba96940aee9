#pragma once
// Feeder relaxation: in the feed zone, each particle's velocity is relaxed towards the belt's,
//   F = m k (V_b t - v),
// with rate k (1/s) and t the belt's direction of travel. It stands in for the loading chute of a
// real conveyor: particles dropped on the belt come to rest on it within a few 1/k instead of
// bouncing and sliding for the whole belt length, so a short belt delivers a quiet, settled layer.
// It is the recipe of the LIGGGHTS virtual rig (datasets/liggghts-rig/README.md: rate 50 1/s, up to
// 50 mm past the end of the insertion face) and is switched off downstream, so the layer reaches the
// pulley carried by belt friction alone (tests/dem_station check that it arrives at belt speed).
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

  void add(const Particles& p, std::vector<Vec3>& force) const {
    if (!(rate > 0.0)) return;
    const Vec3 vb = belt_speed * belt.along;
    for (std::size_t i = 0; i < p.size(); ++i) {
      const double s = belt.s(p.x[i]);
      if (s < s_begin || s > s_end || belt.h(p.x[i]) > h_max) continue;
      force[i] += (p.mass[i] * rate) * (vb - p.v[i]);
    }
  }
};

}  // namespace chutelab::dem::station
