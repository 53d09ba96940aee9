#pragma once
// Hertz normal force with Mindlin no-slip tangential stiffness (reference study §3, Eq 9; EDEM's default model).
//   normal:     F_n = 4/3 E* sqrt(R*) delta^{3/2} + 2 sqrt(5/6) beta sqrt(S_n m*) d(delta)/dt,
//               S_n = 2 E* sqrt(R* delta)  (so the damping term scales as delta^{1/4}, reference study Eq 9)
//   tangential: S_t = 8 G* sqrt(R* delta), damping 2 sqrt(5/6) beta sqrt(S_t m*)
// The spring is HertzMindlinSpring; the damping, with beta = -ln e / sqrt(ln^2 e + pi^2), is the
// restitution damping part (dem/contact/damping_restitution.h) with the spring's Tsuji-type scale
// sqrt(5/6). The tensile tail of the damped force at the end of the contact is kept (as in EDEM and
// LIGGGHTS): with it the realised restitution equals e at every impact speed.
#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <string_view>

#include "dem/contact/damping_restitution.h"
#include "dem/contact/kinematics.h"
#include "dem/contact/law_parameters.h"
#include "dem/contact/mixing.h"
#include "dem/contact/spring_and_damping.h"
#include "dem/timestep.h"

namespace chutelab::dem {

struct HertzMindlinSpring {
  static constexpr std::string_view key = "hertz-mindlin";
  static constexpr std::string_view title = "Hertz-Mindlin";
  static constexpr bool hertz_elastic = true;
  static constexpr bool fixed_tangential_ratio = true;  // S_t / S_n = 4 G* / E*
  static constexpr std::array<LawParameter, 0> parameters{};  // all from the moduli

  struct Coeffs {
    double e_star = 0.0;            // effective Young's modulus E*
    double g_star = 0.0;            // effective shear modulus G*
    double tangential_ratio = 0.0;  // sqrt(S_t / S_n) = sqrt(4 G* / E*)
  };
  static Coeffs mix(const Material& a, const Material& b, const Interaction&) {
    Coeffs c;
    c.e_star = effective_youngs_modulus(a, b);
    c.g_star = effective_shear_modulus(a, b);
    c.tangential_ratio = std::sqrt(4.0 * c.g_star / c.e_star);
    return c;
  }
  static std::string check(const Coeffs&) { return {}; }  // the moduli are checked where they are set

  CHUTELAB_INLINE static SpringForce spring(const Coeffs& c, double delta, double r_eff) {
    const double a = std::sqrt(r_eff * delta);  // Hertz contact radius
    const double sn = 2.0 * c.e_star * a;
    const double st = 8.0 * c.g_star * a;
    return {(2.0 / 3.0) * sn * delta, sn, st, c.tangential_ratio};  // 4/3 E* sqrt(R*) delta^{3/2}
  }
  // The reference study's §3 (Tsuji-type damping of Hertz): a damping ratio sqrt(5/6) beta at the
  // tangent stiffness S_n rebounds with e at any impact speed. To first order in the ratio zeta,
  // 1 - e = pi sqrt(6/5) zeta (the linear spring's pi zeta; tests/dem/test_normal_impact.cpp).
  static double restitution_scale() { return std::sqrt(5.0 / 6.0); }
  static double linear_stiffness(const Coeffs&) { return std::numeric_limits<double>::quiet_NaN(); }
  // The reference study's Eq 11 at impact speed v: the undamped duration, which damping lengthens.
  static double collision_time(const Coeffs& c, double m_eff, double r_eff, double v, double /*zeta*/) {
    return hertz_collision_time(m_eff, r_eff, c.e_star, v);
  }
  // Integral of F_n: 8/15 E* sqrt(R*) delta^{5/2}.
  static double elastic_energy(const Coeffs& c, double delta, double r_eff) {
    return (8.0 / 15.0) * c.e_star * std::sqrt(r_eff) * delta * delta * std::sqrt(delta);
  }
  // Its stiffness follows from the moduli: a collision lasts what they make it last.
  static LawParameters matched_stiffness(double /*zeta*/, double /*m_eff*/, double /*duration*/, double& w0) {
    w0 = std::numeric_limits<double>::quiet_NaN();
    return {};
  }
};

struct HertzMindlin : SpringAndDamping<HertzMindlinSpring, RestitutionDamping> {
  static constexpr std::string_view key = "hertz-mindlin";
  static constexpr std::string_view title = "Hertz-Mindlin";
  static constexpr std::string_view liggghts = "hertz";  // LIGGGHTS' pair model of the same law
  // LIGGGHTS' hertz reads the moduli, restitution and friction every deck writes: nothing more.
  static LawParameters liggghts_pair_properties(const Coeffs&) { return {}; }
};

}  // namespace chutelab::dem
