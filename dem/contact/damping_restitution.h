#pragma once
// Viscous damping set by a coefficient of restitution, the damping part of both the Hertz-Mindlin and
// the linear spring-dashpot law: c = 2 zeta sqrt(k m*), k the stiffness at the overlap (normal, and
// the tangential spring's for the tangential dashpot) and m* the effective mass, with the damping
// ratio zeta = s beta, beta = -ln e / sqrt(ln^2 e + pi^2), and s the spring's restitution_scale().
// For a linear spring (s = 1) beta is the exact damping ratio of an oscillator that rebounds with e;
// for Hertz the reference study's (Tsuji-type) s = sqrt(5/6) gives e at every impact speed (checked
// by tests/dem/test_normal_impact.cpp).
#include <array>
#include <cmath>
#include <numbers>
#include <string>
#include <string_view>

#include "dem/contact/kinematics.h"
#include "dem/contact/law_parameters.h"
#include "dem/material.h"
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

struct RestitutionDamping {
  static constexpr std::string_view key = "restitution";
  static constexpr std::string_view title = "damping from the restitution";
  static constexpr std::array<LawParameter, 0> parameters{};  // the interaction's restitution

  struct Coeffs {
    double factor = 0.0;  // 2 zeta
  };
  template <class Spring>
  static Coeffs set(const Interaction& in) {
    return {2.0 * Spring::restitution_scale() * damping_ratio_from_restitution(in.restitution)};
  }
  static std::string check(const Coeffs&) { return {}; }  // e is checked where it is set

  // A spring that keeps sqrt(kt / kn) per pair (Hertz-Mindlin) saves a square root per contact:
  // sqrt(kt m*) = sqrt(kn m*) sqrt(kt / kn).
  template <class Spring>
  CHUTELAB_INLINE static Dashpot dashpot(const Coeffs& c, const SpringForce& s, double m_eff) {
    const double cn = restitution_damping(c.factor, s.kn, m_eff);
    if constexpr (Spring::fixed_tangential_ratio) return {cn, cn * s.tangential_ratio};
    else return {cn, restitution_damping(c.factor, s.kt, m_eff)};
  }
  static double ratio(const Coeffs& c, double /*stiffness*/, double /*m_eff*/) { return 0.5 * c.factor; }
  static LawParameters matched_parameters(double /*zeta*/, double /*m_eff*/, double /*w0*/) { return {}; }
};

}  // namespace chutelab::dem
