#pragma once
// Hertz normal force with Mindlin no-slip tangential stiffness (reference study §3, Eq 9; EDEM's default model).
//   normal:     F_n = 4/3 E* sqrt(R*) delta^{3/2} + 2 sqrt(5/6) beta sqrt(S_n m*) d(delta)/dt,
//               S_n = 2 E* sqrt(R* delta)  (so the damping term scales as delta^{1/4}, reference study Eq 9)
//   tangential: S_t = 8 G* sqrt(R* delta), damping 2 sqrt(5/6) beta sqrt(S_t m*)
// beta = -ln e / sqrt(ln^2 e + pi^2). The tensile tail of the damped force at the end of the contact is
// kept (as in EDEM and LIGGGHTS): with it the realised restitution equals e at every impact speed.
#include <cmath>

#include "dem/contact/kinematics.h"

namespace chutelab::dem {

struct HertzMindlin {
  CHUTELAB_INLINE static NormalResult normal(const PairCoeffs& c, double delta, double delta_dot, double r_eff,
                             double m_eff) {
    const double a = std::sqrt(r_eff * delta);  // Hertz contact radius
    const double sn = 2.0 * c.e_star * a;
    const double st = 8.0 * c.g_star * a;
    const double elastic = (2.0 / 3.0) * sn * delta;  // = 4/3 E* sqrt(R*) delta^{3/2}
    const double q = c.hertz_damping * std::sqrt(sn * m_eff);
    // sqrt(S_t m*) = sqrt(S_n m*) sqrt(4 G*/E*): one square root fewer per contact.
    return {elastic + q * delta_dot, sn, st, q * c.hertz_tangential_ratio};
  }
  // Elastic energy stored at overlap delta: integral of F_n = 8/15 E* sqrt(R*) delta^{5/2}.
  static double elastic_energy(const PairCoeffs& c, double delta, double r_eff) {
    return (8.0 / 15.0) * c.e_star * std::sqrt(r_eff) * delta * delta * std::sqrt(delta);
  }
};

}  // namespace chutelab::dem
