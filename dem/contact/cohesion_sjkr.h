#pragma once
// Optional cohesion hook, simplified JKR: an attractive normal force equal to a cohesion energy density
// times the contact area, F_c = k_c pi a^2 with a^2 = R* delta (Hertz contact radius). Zero unless the
// material pair sets cohesion_energy_density.
#include <numbers>

#include "dem/material.h"
#include "dem/types.h"

namespace chutelab::dem {

CHUTELAB_INLINE double cohesion_sjkr(const PairCoeffs& c, double delta, double r_eff) {
  return c.cohesion * std::numbers::pi * r_eff * delta;
}

}  // namespace chutelab::dem
