#pragma once
// Hertz normal force with Mindlin no-slip tangential stiffness (reference study §3, Eq 9; EDEM's default model).
//   normal:     F_n = 4/3 E* sqrt(R*) delta^{3/2} + 2 sqrt(5/6) beta sqrt(S_n m*) d(delta)/dt,
//               S_n = 2 E* sqrt(R* delta)  (so the damping term scales as delta^{1/4}, reference study Eq 9)
//   tangential: S_t = 8 G* sqrt(R* delta), damping 2 sqrt(5/6) beta sqrt(S_t m*)
// beta = -ln e / sqrt(ln^2 e + pi^2) (dem/contact/damping_restitution.h). The tensile tail of the
// damped force at the end of the contact is kept (as in EDEM and LIGGGHTS): with it the realised
// restitution equals e at every impact speed.
#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <string_view>

#include "dem/contact/damping_restitution.h"
#include "dem/contact/kinematics.h"
#include "dem/contact/law_parameters.h"
#include "dem/contact/mixing.h"
#include "dem/timestep.h"

namespace chutelab::dem {

struct HertzMindlin {
  static constexpr std::string_view key = "hertz-mindlin";
  static constexpr std::string_view title = "Hertz-Mindlin";
  static constexpr std::string_view liggghts = "hertz";  // LIGGGHTS' pair model of the same law
  static constexpr bool hertz_elastic = true;
  static constexpr std::array<LawParameter, 0> parameters{};  // all from the moduli and e

  struct Coeffs {
    double e_star = 0.0;            // effective Young's modulus E*
    double g_star = 0.0;            // effective shear modulus G*
    double damping = 0.0;           // 2 sqrt(5/6) beta
    double tangential_ratio = 0.0;  // sqrt(S_t / S_n) = sqrt(4 G* / E*)
  };
  static Coeffs mix(const Material& a, const Material& b, const Interaction& in) {
    Coeffs c;
    c.e_star = effective_youngs_modulus(a, b);
    c.g_star = effective_shear_modulus(a, b);
    // The reference study's §3 (Tsuji-type damping of Hertz): F_d = 2 sqrt(5/6) beta sqrt(S_n m*) v_n.
    // With the tensile tail of the force allowed this reproduces e exactly for any impact speed.
    c.damping = 2.0 * std::sqrt(5.0 / 6.0) * damping_ratio_from_restitution(in.restitution);
    c.tangential_ratio = std::sqrt(4.0 * c.g_star / c.e_star);
    return c;
  }
  static std::string check(const Coeffs&) { return {}; }  // the moduli and e are checked where they are set

  CHUTELAB_INLINE static NormalResult normal(const Coeffs& c, double delta, double delta_dot, double r_eff,
                                             double m_eff) {
    const double a = std::sqrt(r_eff * delta);  // Hertz contact radius
    const double sn = 2.0 * c.e_star * a;
    const double st = 8.0 * c.g_star * a;
    const double elastic = (2.0 / 3.0) * sn * delta;  // = 4/3 E* sqrt(R*) delta^{3/2}
    const double q = restitution_damping(c.damping, sn, m_eff);
    // sqrt(S_t m*) = sqrt(S_n m*) sqrt(4 G*/E*): one square root fewer per contact.
    return {elastic + q * delta_dot, sn, st, q * c.tangential_ratio};
  }
  // The reference study's Eq 11 at impact speed v.
  static double collision_time(const Coeffs& c, double m_eff, double r_eff, double v) {
    return hertz_collision_time(m_eff, r_eff, c.e_star, v);
  }
  // Integral of F_n: 8/15 E* sqrt(R*) delta^{5/2}.
  static double elastic_energy(const Coeffs& c, double delta, double r_eff) {
    return (8.0 / 15.0) * c.e_star * std::sqrt(r_eff) * delta * delta * std::sqrt(delta);
  }
  // Its stiffness follows from the moduli: a collision lasts what they make it last.
  static LawParameters matched_parameters(double /*restitution*/, double /*m_eff*/, double /*duration*/) { return {}; }
  // LIGGGHTS' hertz reads the moduli, restitution and friction every deck writes: nothing more.
  static LawParameters liggghts_pair_properties(const Coeffs&) { return {}; }
};

}  // namespace chutelab::dem
