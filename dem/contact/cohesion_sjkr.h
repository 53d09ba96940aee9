#pragma once
// Cohesion, simplified JKR: an attractive normal force equal to a cohesion energy density times the
// contact area, F_c = k_c pi a^2 with a^2 = R* delta (Hertz contact radius). A part of the contact
// model of its own (ContactModel's Cohesion): the World runs CohesionSjkr only when some material
// pair sets cohesion_energy_density, and NoCohesion otherwise.
#include <numbers>

#include "dem/contact/kinematics.h"
#include "dem/contact/pair_coeffs.h"

namespace chutelab::dem {

struct CohesionSjkr {
  CHUTELAB_INLINE static void apply(const SharedCoeffs& c, double delta, double r_eff, NormalResult& nr) {
    nr.force -= c.cohesion * std::numbers::pi * r_eff * delta;
  }
};

struct NoCohesion {
  CHUTELAB_INLINE static void apply(const SharedCoeffs&, double, double, NormalResult&) {}
};

}  // namespace chutelab::dem
