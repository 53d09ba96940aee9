#pragma once
// Viscous normal damping set by a coefficient of restitution, the damping of both the Hertz-Mindlin
// and the linear spring-dashpot law: F_d = c_n d(delta)/dt with c_n = factor sqrt(k m*), k the normal
// stiffness at the overlap and m* the effective mass. For a linear spring the factor 2 beta, with
// beta = -ln e / sqrt(ln^2 e + pi^2), is the exact damping ratio of an oscillator that rebounds with
// e; for Hertz the reference study's (Tsuji-type) 2 sqrt(5/6) beta gives e at every impact speed (checked by
// tests/dem/test_normal_impact.cpp). The tangential spring's damping uses its own stiffness.
#include <cmath>
#include <numbers>

#include "dem/types.h"

namespace chutelab::dem {

// beta of the reference study's damping formula for restitution e: -ln e / sqrt(ln^2 e + pi^2).
inline double damping_ratio_from_restitution(double e) {
  if (e >= 1.0) return 0.0;
  const double l = std::log(e);
  return -l / std::sqrt(l * l + std::numbers::pi * std::numbers::pi);
}

// c = factor sqrt(k m*), N s/m.
CHUTELAB_INLINE double restitution_damping(double factor, double stiffness, double m_eff) {
  return factor * std::sqrt(stiffness * m_eff);
}

}  // namespace chutelab::dem
